// kerf sim run [SCENE] [--steps N] [--vtu-out DIR]: runs a scene headless (an embedded scene
// by name, or a text-format scene file; lattice-tension if none) and prints what it did; with
// --vtu-out, writes about a hundred VTU frames and a .pvd collection that ParaView opens as a time
// series. kerf sim list: the embedded scenes.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace kerf::cli {

absl::StatusOr<std::string> RunSimCommand(const std::vector<absl::string_view>& args);

}  // namespace kerf::cli
