// Where a segment crosses a triangle: the test behind edge intersections (a tet edge against
// the blade's swept surface) and face intersections (the blade tip's path against a tet face).
#pragma once

#include <Eigen/Core>
#include <optional>

namespace kerf::geometry {

struct SegmentTriangleCrossing {
  double t;  // the crossing is p + t (q - p), t in [0, 1]
  // Barycentric coordinates of the crossing on triangle (a, b, c): non-negative, sum 1.
  Eigen::Vector3d barycentric;
};

// The crossing of segment pq with triangle abc, boundaries included (a segment through a
// triangle's edge or corner, or ending on the triangle, crosses it). nullopt when the segment
// misses the triangle, lies in its plane (both ends within a billionth of its length of it,
// where the sides' signs are rounding), or either is degenerate: a segment in the plane of a face
// is a degenerate blade that cutting handles apart.
std::optional<SegmentTriangleCrossing> IntersectSegmentTriangle(const Eigen::Vector3d& p,
                                                                const Eigen::Vector3d& q,
                                                                const Eigen::Vector3d& a,
                                                                const Eigen::Vector3d& b,
                                                                const Eigen::Vector3d& c);

}  // namespace kerf::geometry
