// Invariants checked in every build: a broken one stops the program with the condition and
// where it was written, instead of going on with a wrong state (assert is off where NDEBUG is
// set). For conditions that only a bug can break; errors a caller can handle are absl::Status.
#pragma once

#include <cstdio>
#include <cstdlib>

#define KERF_CHECK(condition)                                                            \
  do {                                                                                   \
    if (!(condition)) {                                                                  \
      std::fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #condition); \
      std::abort();                                                                      \
    }                                                                                    \
  } while (false)
