// Where the blade went inside one tet: samples of the surface its edge swept, named by their
// barycentric weights on the tet's corners, so a split of the tet for good can be judged against
// the blade's path (at rest positions, through the weights, however the tissue moved since).
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "cut/swept_path.h"

namespace kerf::cut {

// The point at barycentric `weights` on `corners`.
inline Eigen::Vector3d PointAtWeights(const std::array<Eigen::Vector3d, 4>& corners,
                                      const Eigen::Vector4d& weights) {
  return weights[0] * corners[0] + weights[1] * corners[1] + weights[2] * corners[2] +
         weights[3] * corners[3];
}

// Points along the blade (tip to heel) per pose sampled, and poses sampled per step (its two
// ends and its middle).
inline constexpr int kBladeSamples = 21;
// Steps sampled at the most, spread evenly over those that meet the tet (a blade held in a tet
// for a second makes a thousand steps, each a hundredth of an edge from the last).
inline constexpr int kSampledSteps = 64;

// The samples of the steps of `path` from pose `first` to pose `last` (each pair of consecutive
// poses) that lie inside the tet with corners `corners` (the positions the poses were taken in, not
// flat), as weights on those corners. A step whose box misses the tet's is passed over; of more
// than kSampledSteps that meet it, that many spread evenly are sampled. `tip_inside`, if given, is
// set to whether a sample at the blade's tip lies inside.
std::vector<Eigen::Vector4d> StepSamplesIn(const std::array<Eigen::Vector3d, 4>& corners,
                                           const SweptPath& path, std::size_t first,
                                           std::size_t last, bool* tip_inside = nullptr);

// At most `at_most` of `samples`, spread evenly from the first (every k-th, k the least that
// keeps them within the bound: all of them where there are fewer).
std::vector<Eigen::Vector4d> SpreadEvenly(const std::vector<Eigen::Vector4d>& samples,
                                          std::size_t at_most);

// The samples tip + j along (0 <= j < kBladeSamples) inside the box from `low` to `high`: those
// from the first to the second, within [0, kBladeSamples), or none (the second smaller).
std::pair<int, int> SamplesInBox(const Eigen::Vector3d& tip, const Eigen::Vector3d& along,
                                 const Eigen::Vector3d& low, const Eigen::Vector3d& high);

// How far samples lie from a set of triangles: the farthest (its weights and distance, m) and
// how many lie farther than a reach.
struct SamplesFrom {
  Eigen::Vector4d farthest = Eigen::Vector4d::Zero();
  double distance = 0;
  int beyond = 0;
};
// Of `samples` (weights on the corners `rest`) against the triangles `triangles` (rest
// positions; every sample infinitely far where there are none) and `reach` (m).
SamplesFrom Measure(const std::vector<Eigen::Vector4d>& samples,
                    const std::array<Eigen::Vector3d, 4>& rest,
                    const std::vector<std::array<Eigen::Vector3d, 3>>& triangles, double reach);

}  // namespace kerf::cut
