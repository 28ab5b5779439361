// kerf experiment stability: the stability matrix. Every standard scene and cut
// (lab/standard_scenes.h: the lattice under tension, a deliberately poor-quality lattice, the
// liver of ../shared/meshes when its file is given) is cut live (lab/live_cut.h) by each
// integrator (explicit at 0.9 of the critical step re-estimated after every cut, explicit in
// sub-steps of 1 ms, backward Euler at 1 ms) with each elastic law (linear, corotational),
// cut progressively (the default) and deferred, each without and with snapping at
// kStabilitySnapFraction.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "kerf/v1/live_cut_report.pb.h"
#include "lab/live_cut.h"

namespace kerf::cli {

// The snapping rows' fraction: the open cutters' 0.2 of an edge (../shared/design/cutting.md).
inline constexpr double kStabilitySnapFraction = 0.2;

// A live-cut row of the experiments (this matrix, `kerf experiment live-cut`) stops after this
// much wall time (s): a row that does not blow up among slivers may crawl, and at that rate it
// is far from real time anyway.
inline constexpr double kRowWallSeconds = 30;

struct StabilityOptions {
  std::vector<std::string> scenes = {"lattice-tension", "lattice-poor"};
  std::string liver_mesh_path;  // adds the liver when set
  lab::LiveCutOptions live_cut = {.max_wall_seconds = kRowWallSeconds};
};

absl::StatusOr<kerf::v1::StabilityExperiment> RunStability(const StabilityOptions& options);

// The matrix as one Markdown table.
std::string FormatStability(const kerf::v1::StabilityExperiment& experiment);

// A row's "stopped after (s)" table cell: "-" for a row that ran to its end or blew up.
std::string StoppedAfterCell(const kerf::v1::LiveCutRow& row);

}  // namespace kerf::cli
