#include "cut/steps_in_tet.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "geometry/point_triangle_distance.h"

namespace kerf::cut {

std::pair<int, int> SamplesInBox(const Eigen::Vector3d& tip, const Eigen::Vector3d& along,
                                 const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  double from = 0, to = kBladeSamples - 1;
  for (int axis = 0; axis < 3; ++axis) {
    if (along[axis] == 0) {
      if (tip[axis] < low[axis] || tip[axis] > high[axis]) return {0, -1};
      continue;
    }
    const double at_low = (low[axis] - tip[axis]) / along[axis];
    const double at_high = (high[axis] - tip[axis]) / along[axis];
    from = std::max(from, std::min(at_low, at_high));
    to = std::min(to, std::max(at_low, at_high));
  }
  if (!(from <= to)) return {0, -1};  // none, or not finite (a blade nearly along an axis)
  return {static_cast<int>(std::ceil(from)), static_cast<int>(std::floor(to))};
}

std::vector<Eigen::Vector4d> SpreadEvenly(const std::vector<Eigen::Vector4d>& samples,
                                          std::size_t at_most) {
  std::vector<Eigen::Vector4d> spread;
  const std::size_t stride = samples.size() / at_most + 1;
  for (std::size_t i = 0; i < samples.size(); i += stride) spread.push_back(samples[i]);
  return spread;
}

std::vector<Eigen::Vector4d> StepSamplesIn(const std::array<Eigen::Vector3d, 4>& corners,
                                           const SweptPath& path, std::size_t first,
                                           std::size_t last, bool* tip_inside) {
  if (tip_inside != nullptr) *tip_inside = false;
  std::vector<Eigen::Vector4d> samples;
  Eigen::Matrix3d frame;
  frame << corners[1] - corners[0], corners[2] - corners[0], corners[3] - corners[0];
  const Eigen::Matrix3d to_weights = frame.inverse();
  Eigen::Vector3d low = corners[0], high = corners[0];
  for (const Eigen::Vector3d& c : corners) low = low.cwiseMin(c), high = high.cwiseMax(c);
  std::vector<std::size_t> steps;  // those whose box meets the tet's
  path.ForEachStepNear(first, last, low, high, 0, [&](std::size_t i) {
    steps.push_back(i);
    return true;
  });
  const std::size_t taken = std::min(steps.size(), std::size_t{kSampledSteps});
  for (std::size_t k = 0; k < taken; ++k) {
    const std::size_t i = steps[k * steps.size() / taken];
    const BladePose& a = path.at(i);
    const BladePose& b = path.at(i + 1);
    for (const double s : {0.0, 0.5, 1.0}) {
      const Eigen::Vector3d tip = (1 - s) * a.tip + s * b.tip;
      const Eigen::Vector3d heel = (1 - s) * a.heel + s * b.heel;
      const Eigen::Vector3d along = (heel - tip) / double(kBladeSamples - 1);
      const auto [from, to] = SamplesInBox(tip, along, low, high);
      for (int j = from; j <= to; ++j) {
        const Eigen::Vector3d x = tip + along * j;
        const Eigen::Vector3d w = to_weights * (x - corners[0]);
        const Eigen::Vector4d weights(1 - w.sum(), w.x(), w.y(), w.z());
        if (weights.minCoeff() < 0) continue;
        samples.push_back(weights);
        if (j == 0 && tip_inside != nullptr) *tip_inside = true;
      }
    }
  }
  return samples;
}

SamplesFrom Measure(const std::vector<Eigen::Vector4d>& samples,
                    const std::array<Eigen::Vector3d, 4>& rest,
                    const std::vector<std::array<Eigen::Vector3d, 3>>& triangles, double reach) {
  SamplesFrom from;
  for (const Eigen::Vector4d& w : samples) {
    const Eigen::Vector3d x = PointAtWeights(rest, w);
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& t : triangles) {
      nearest = std::min(nearest, geometry::DistanceToTriangle(x, t[0], t[1], t[2]));
      if (nearest <= reach && nearest <= from.distance) break;  // neither counts nor is farthest
    }
    if (nearest > reach) ++from.beyond;
    if (nearest > from.distance) from.farthest = w, from.distance = nearest;
  }
  return from;
}

}  // namespace kerf::cut
