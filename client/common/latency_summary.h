// Order statistics of a set of measurements (latencies, intervals), in their own unit.
#pragma once

#include <cstddef>
#include <vector>

namespace kerf::client {

struct Summary {
  std::size_t count = 0;
  double p50 = 0, p90 = 0, p99 = 0, max = 0, mean = 0;
};

// Nearest-rank percentiles; all zero for no values.
Summary Summarize(std::vector<double> values);

}  // namespace kerf::client
