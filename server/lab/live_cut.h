// A cut made while the tissue moves, as in a session: the scene settles, then the blade
// follows a path at a fixed pose rate with the simulation stepping between poses. What
// `kerf experiment live-cut` runs per integrator and cut mode, to show where explicit
// integration blows up and what keeps it stable.
#pragma once

#include <limits>
#include <vector>

#include "absl/status/statusor.h"
#include "cut/blade.h"
#include "kerf/v1/live_cut_report.pb.h"
#include "sim/scene.h"

namespace kerf::lab {

struct LiveCutOptions {
  double settle_seconds = 1;  // simulated before the first pose
  double slow_down = 16;      // the path is followed this many times slower than written
  double pose_rate_hz = 1000;
  double blow_up_energy_ratio = 10;  // see kerf.v1.LiveCutRow.blew_up
  // A run whose poses and steps have taken this long (wall s) stops there (see
  // kerf.v1.LiveCutRow.stopped_after).
  double max_wall_seconds = std::numeric_limits<double>::infinity();
};

// Runs `scene` (explicit or implicit; STATIC is FAILED_PRECONDITION) with the blade along
// `path` (times from 0, as written), interpolated linearly to the pose rate, and withdraws
// it at the end. Fills every field of the row but `integration`, `cut_mode`, `scene`, `path`
// and `law`. A pose the cutter refuses is returned as its error. The wall time is measured, so
// that field alone differs between runs.
absl::StatusOr<kerf::v1::LiveCutRow> RunLiveCut(sim::Scene scene,
                                                const std::vector<cut::BladePose>& path,
                                                const LiveCutOptions& options);

}  // namespace kerf::lab
