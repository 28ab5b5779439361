// kerf chart TRADEOFF.json --out PREFIX: draws what `kerf experiment tradeoff --json` printed
// as PREFIX.svg and PREFIX.png (gnuplot, installed by scripts/setup): one panel per bar, wall
// time per simulated second against error on log scales, a mark per integrator and a colour
// per elastic law, the resolution n beside each point, the Pareto front as a line and the
// default configuration circled.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace kerf::cli {

// Prints the two files' names. INVALID_ARGUMENT for a file that is not a tradeoff report or
// has no row; the errors of RunExternalProgram for gnuplot.
absl::StatusOr<std::string> RunChartCommand(const std::vector<absl::string_view>& args);

}  // namespace kerf::cli
