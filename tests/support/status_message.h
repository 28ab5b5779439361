// A status message as std::string, so GoogleTest prints it as text in failures.
#pragma once

#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace kerf::testing {

inline std::string StatusMessage(const absl::Status& status) {
  return std::string(status.message());
}

template <typename T>
std::string StatusMessage(const absl::StatusOr<T>& result) {
  return std::string(result.status().message());
}

}  // namespace kerf::testing
