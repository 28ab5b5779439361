#include "geometry/segment_distance.h"

#include <algorithm>

namespace kerf::geometry {

double DistanceToSegment(const Eigen::Vector3d& x, const Eigen::Vector3d& p,
                         const Eigen::Vector3d& q) {
  const Eigen::Vector3d d = q - p;
  const double length_squared = d.squaredNorm();
  const double s = length_squared > 0 ? std::clamp((x - p).dot(d) / length_squared, 0.0, 1.0) : 0;
  return (x - (p + s * d)).norm();
}

ClosestPoints ClosestPointsOfSegments(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                      const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  // Minimise |p + s d1 - a - t d2|^2 over the unit square (Ericson, Real-Time Collision
  // Detection, 5.1.9).
  const Eigen::Vector3d d1 = q - p, d2 = b - a, r = p - a;
  const double aa = d1.squaredNorm(), ee = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, t = 0;
  if (aa <= 0 && ee <= 0) {
    // Both are points.
  } else if (aa <= 0) {
    t = std::clamp(f / ee, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (ee <= 0) {
      s = std::clamp(-c / aa, 0.0, 1.0);
    } else {
      const double bb = d1.dot(d2), denominator = aa * ee - bb * bb;
      s = denominator > 0 ? std::clamp((bb * f - c * ee) / denominator, 0.0, 1.0) : 0;
      t = (bb * s + f) / ee;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / aa, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((bb - c) / aa, 0.0, 1.0);
      }
    }
  }
  return {s, t, ((p + s * d1) - (a + t * d2)).norm()};
}

}  // namespace kerf::geometry
