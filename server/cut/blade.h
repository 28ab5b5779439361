// Blade poses as the cutter takes them, and the checks that keep bad input out: a pose that
// is not finite, goes back in time, has no length, or jumps too far for one step is refused
// with a message and changes nothing.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "absl/status/status.h"

namespace kerf::cut {

struct BladePose {
  double time = 0;  // s
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
  Eigen::Vector3d heel = Eigen::Vector3d::Zero();
};

struct BladeLimits {
  // The longest blade, m.
  double max_length = 0.1;
  // How far the tip or heel may move from one pose to the next, m: farther is a teleport.
  double max_step = 0.02;
  // How fast the tip or heel may move, m/s (a surgeon's hand stays well under 1 m/s).
  double max_speed = 2.0;
};

// OK, or INVALID_ARGUMENT naming the value. `previous` is null for the first pose of a path.
absl::Status ValidatePose(const BladePose& pose, const BladePose* previous,
                          const BladeLimits& limits);

// The pose at `time` on the straight motion from a to b (a.time < b.time): tip and heel
// linear in time.
BladePose InterpolatePose(const BladePose& a, const BladePose& b, double time);

// The surface the blade's edge sweeps from `from` to `to`: triangles (tip, heel, heel') and
// (tip, heel', tip') (shared/design/cutting.md).
std::array<std::array<Eigen::Vector3d, 3>, 2> SweptTriangles(const BladePose& from,
                                                             const BladePose& to);
// The distance from `x` to that surface.
double DistanceToSweep(const Eigen::Vector3d& x, const BladePose& from, const BladePose& to);

}  // namespace kerf::cut
