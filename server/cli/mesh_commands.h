// The `kerf mesh ...` and `kerf demo` subcommands. Each returns what it printed on success;
// errors are returned to main, which prints them and sets the exit code.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace kerf::cli {

// kerf mesh info FILE [--json]
// kerf mesh lattice NX NY NZ [--size X Y Z] --out FILE
// kerf mesh convert IN OUT
absl::StatusOr<std::string> RunMeshCommand(const std::vector<absl::string_view>& args);

// kerf demo: the embedded default, the paper's 4x6x4 lattice, and its statistics.
absl::StatusOr<std::string> RunDemoCommand(const std::vector<absl::string_view>& args);

inline constexpr absl::string_view kMeshUsage =
    "kerf mesh info FILE [--json]\n"
    "       kerf mesh lattice NX NY NZ [--size X Y Z] --out FILE\n"
    "       kerf mesh convert IN OUT";

}  // namespace kerf::cli
