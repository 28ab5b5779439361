#include "cut/blade.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"
#include "geometry/point_triangle_distance.h"

namespace kerf::cut {

absl::Status ValidatePose(const BladePose& pose, const BladePose* previous,
                          const BladeLimits& limits) {
  if (!std::isfinite(pose.time) || !pose.tip.allFinite() || !pose.heel.allFinite()) {
    return absl::InvalidArgumentError("the pose has a non-finite time, tip or heel");
  }
  const double length = (pose.tip - pose.heel).norm();
  if (!(length > 0) || length > limits.max_length) {
    return absl::InvalidArgumentError(absl::StrCat("the blade is ", length,
                                                   " m long; it must be longer than 0 and at "
                                                   "most ",
                                                   limits.max_length, " m"));
  }
  if (previous == nullptr) return absl::OkStatus();
  const double dt = pose.time - previous->time;
  if (!(dt > 0)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "time ", pose.time, " s does not follow the previous pose's ", previous->time, " s"));
  }
  const double travel =
      std::max((pose.tip - previous->tip).norm(), (pose.heel - previous->heel).norm());
  if (travel > limits.max_step) {
    return absl::InvalidArgumentError(absl::StrCat(
        "the blade jumps ", travel, " m in one pose; at most ", limits.max_step, " m is accepted"));
  }
  if (travel / dt > limits.max_speed) {
    return absl::InvalidArgumentError(absl::StrCat("the blade moves at ", travel / dt,
                                                   " m/s; at most ", limits.max_speed,
                                                   " m/s is accepted"));
  }
  return absl::OkStatus();
}

BladePose InterpolatePose(const BladePose& a, const BladePose& b, double time) {
  const double s = (time - a.time) / (b.time - a.time);
  return {time, a.tip + s * (b.tip - a.tip), a.heel + s * (b.heel - a.heel)};
}

std::array<std::array<Eigen::Vector3d, 3>, 2> SweptTriangles(const BladePose& from,
                                                             const BladePose& to) {
  return {{{from.tip, from.heel, to.heel}, {from.tip, to.heel, to.tip}}};
}

double DistanceToSweep(const Eigen::Vector3d& x, const BladePose& from, const BladePose& to) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& t : SweptTriangles(from, to)) {
    nearest = std::min(nearest, geometry::DistanceToTriangle(x, t[0], t[1], t[2]));
  }
  return nearest;
}

}  // namespace kerf::cut
