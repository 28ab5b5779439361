// One load test against a kerf-server: N sessions, each with one cutter repeating a blade path
// in real time and M observers, for a bounded time and a bounded number of poses; then the
// sessions are closed (which ends the observers' streams) and everything is counted.
#pragma once

#include <atomic>
#include <functional>
#include <string>

#include "absl/status/statusor.h"
#include "kerf/v1/blade.pb.h"
#include "kerf/v1/load.pb.h"

namespace kerf::client {

struct LoadTarget {
  std::string server;  // host:port
  std::string tls_ca;  // empty: plaintext
};

// Where the run stands, for a progress display (read from another thread).
struct LoadProgress {
  std::atomic<std::uint64_t> poses_sent{0};
  std::atomic<std::uint64_t> frames{0};  // cutters' and observers'
  std::atomic<std::uint64_t> errors{0};
};

// Runs `scenario` with `path` (already read). INVALID_ARGUMENT for a scenario out of bounds
// (no session, over 64 sessions or 256 observers per session, a duration outside (0, 3600] s),
// UNAVAILABLE when no session can be made. Errors of single streams are counted in the report,
// not returned.
absl::StatusOr<kerf::v1::LoadReport> RunLoad(const LoadTarget& target,
                                             const kerf::v1::LoadScenario& scenario,
                                             const kerf::v1::BladePath& path,
                                             LoadProgress* progress);

// Fills report.objective_met and objective_missed from `objective`.
void CheckObjective(const kerf::v1::LoadObjective& objective, kerf::v1::LoadReport* report);

}  // namespace kerf::client
