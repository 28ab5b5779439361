#include "geometry/point_triangle_distance.h"

#include <Eigen/Geometry>
#include <algorithm>

namespace kerf::geometry {
namespace {

Eigen::Vector3d ClosestOnSegment(const Eigen::Vector3d& x, const Eigen::Vector3d& p,
                                 const Eigen::Vector3d& q) {
  const Eigen::Vector3d d = q - p;
  const double length_squared = d.squaredNorm();
  const double s = length_squared > 0 ? std::clamp((x - p).dot(d) / length_squared, 0.0, 1.0) : 0;
  return p + s * d;
}

}  // namespace

Eigen::Vector3d ClosestPointOnTriangle(const Eigen::Vector3d& x, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  // Voronoi regions of the corners, then of the edges, else the inside (Ericson, Real-Time
  // Collision Detection, 5.1.5), with degenerate triangles taken as their longest edge.
  const Eigen::Vector3d ab = b - a, ac = c - a;
  if (ab.cross(ac).squaredNorm() <= 1e-30 * ab.squaredNorm() * ac.squaredNorm() ||
      ab.squaredNorm() == 0 || ac.squaredNorm() == 0) {
    const Eigen::Vector3d candidates[3] = {ClosestOnSegment(x, a, b), ClosestOnSegment(x, b, c),
                                           ClosestOnSegment(x, c, a)};
    const Eigen::Vector3d* best = &candidates[0];
    for (const Eigen::Vector3d& p : candidates) {
      if ((p - x).squaredNorm() < (*best - x).squaredNorm()) best = &p;
    }
    return *best;
  }
  const Eigen::Vector3d ax = x - a;
  const double d1 = ab.dot(ax), d2 = ac.dot(ax);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bx = x - b;
  const double d3 = ab.dot(bx), d4 = ac.dot(bx);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cx = x - c;
  const double d5 = ab.dot(cx), d6 = ac.dot(cx);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const double denominator = 1 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

double DistanceToTriangle(const Eigen::Vector3d& x, const Eigen::Vector3d& a,
                          const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return (x - ClosestPointOnTriangle(x, a, b, c)).norm();
}

}  // namespace kerf::geometry
