#include "geometry/segment_box.h"

#include <algorithm>
#include <cmath>

namespace kerf::geometry {

bool SegmentMeetsBox(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& lo,
                     const Eigen::Vector3d& hi, double margin) {
  // The parameters t in [0, 1] of p + t (q - p) inside each slab, intersected.
  double enter = 0, leave = 1;
  for (int axis = 0; axis < 3; ++axis) {
    const double low = lo[axis] - margin, high = hi[axis] + margin;
    const double d = q[axis] - p[axis];
    if (d == 0) {
      if (p[axis] < low || p[axis] > high) return false;
      continue;
    }
    double t0 = (low - p[axis]) / d, t1 = (high - p[axis]) / d;
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
    if (enter > leave) return false;
  }
  return true;
}

}  // namespace kerf::geometry
