// Distances to and between segments.
#pragma once

#include <Eigen/Core>

namespace kerf::geometry {

// The distance (m) from `x` to the closest point of the segment p-q (p itself if p == q).
double DistanceToSegment(const Eigen::Vector3d& x, const Eigen::Vector3d& p,
                         const Eigen::Vector3d& q);

// The closest points of segments p-q and a-b: p + s (q - p) and a + t (b - a), s and t in
// [0, 1], and their distance (m). For parallel segments, one of the closest pairs.
struct ClosestPoints {
  double s = 0;
  double t = 0;
  double distance = 0;
};
ClosestPoints ClosestPointsOfSegments(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                      const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace kerf::geometry
