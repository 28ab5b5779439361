// kerf path FAMILY MESH --out PATH.json [--seed N] [--duration S] [--rate HZ]: writes a seeded
// hand-like blade path across a mesh file or a scene (lab::MakeHandPath; FAMILY is hand,
// vertices, edges or face-plane), in the form kerf cut --path reads.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace kerf::cli {

absl::StatusOr<std::string> RunPathCommand(const std::vector<absl::string_view>& args);

}  // namespace kerf::cli
