// kerf experiment tradeoff: speed against accuracy. Each bar of lab/accuracy_bar.h, at each
// resolution, with each elastic law and each integrator, settles from a start near its answer;
// a row records the wall time per simulated second and the error against CalculiX on
// quadratic tets (cli/experiments/calculix_reference.h). `kerf chart` draws the rows.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "kerf/v1/tradeoff_report.pb.h"

namespace kerf::cli {

struct TradeoffOptions {
  std::vector<int> resolutions = {2, 4, 6, 8};  // n of each row, even
  int reference_resolution = 6;                 // n of the CalculiX reference
  double settle_seconds = 4;  // simulated per row; the slowest mode decays by about e^-11
  double mass_damping = 6;    // 1/s: about critical for the cantilever's first mode
};

absl::StatusOr<kerf::v1::TradeoffExperiment> RunTradeoff(const TradeoffOptions& options);

// One table per bar, in Markdown.
std::string FormatTradeoff(const kerf::v1::TradeoffExperiment& experiment);

// Marks the rows on each bar's Pareto front (see kerf.v1.TradeoffRow.pareto).
void MarkParetoFront(kerf::v1::TradeoffExperiment* experiment);

}  // namespace kerf::cli
