// Running the kerf binary the test target was built beside (KERF_BINARY), as a user would.
#pragma once

#include <string>

#include "absl/strings/str_cat.h"
#include "support/run_command.h"

namespace kerf::testing {

// `kerf ARGS` in a shell; its output is stdout and stderr together.
inline CommandResult Kerf(const std::string& args) {
  return RunCommand(absl::StrCat(KERF_BINARY, " ", args, " 2>&1"));
}

}  // namespace kerf::testing
