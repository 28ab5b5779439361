// kerf experiment NAME [--json]: the project's repeatable experiments.
//   lattice-cut: the paper's experiment (Mor & Kanade 2000, section 6): the 4x6x4 lattice of
//   576 tets held at equilibrium under 10% tension (scene lattice-tension, solved statically),
//   cut along the blade paths in server/lab/paths/ (a straight cut through the whole depth
//   across the pull, and a curved cut 2 cm deep), reported beside the paper's figures.
//   progressive-cases: scripted paths that reach each case of the paper's Table 1.
//   live-cut: lattice-tension cut straight through while it moves (lab/live_cut.h), with
//   explicit integration at 1 ms, explicit at 0.9 of a re-estimated critical step, and
//   backward Euler at 1 ms, each cutting deferred and progressively: which blow up, and why.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace kerf::cli {

absl::StatusOr<std::string> RunExperimentCommand(const std::vector<absl::string_view>& args);

}  // namespace kerf::cli
