// kerf experiment hand-cuts [--meshes FILE,...] [--seeds N] [--check every|end] [--json]: each
// cutting mode (progressive, deferred) along seeded hand-like paths of every family
// (lab::MakeHandPath) through each mesh:
// where the cut is against the path (lab::FidelityMeter), its quality, its lag (with
// --check every) and its time per pose. Meshes: the paper's 4 x 6 x 4 cm lattice at rest, unless
// --meshes names mesh files or scenes.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "cli/command_args.h"

namespace kerf::cli {

absl::StatusOr<std::string> RunHandCutExperiment(CommandArgs* args, bool json);

}  // namespace kerf::cli
