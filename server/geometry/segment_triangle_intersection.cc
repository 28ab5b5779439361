#include "geometry/segment_triangle_intersection.h"

#include <Eigen/Geometry>
#include <cmath>

#include "geometry/tet_measures.h"

namespace kerf::geometry {
namespace {

// A segment whose ends lie within this share of its length of the triangle's plane lies in it.
constexpr double kInPlaneShare = 1e-9;

}  // namespace

std::optional<SegmentTriangleCrossing> IntersectSegmentTriangle(const Eigen::Vector3d& p,
                                                                const Eigen::Vector3d& q,
                                                                const Eigen::Vector3d& a,
                                                                const Eigen::Vector3d& b,
                                                                const Eigen::Vector3d& c) {
  // Which side of the triangle's plane each end is on.
  const double side_p = SignedVolume(a, b, c, p);
  const double side_q = SignedVolume(a, b, c, q);
  if ((side_p > 0 && side_q > 0) || (side_p < 0 && side_q < 0) || side_p == side_q) {
    return std::nullopt;  // both on one side, or both in the plane
  }
  // Both ends within rounding of the plane (a billionth of the segment's length): the signs are
  // noise, and so would be the crossing.
  const double in_plane = kInPlaneShare * (q - p).norm() * (b - a).cross(c - a).norm() / 6;
  if (std::abs(side_p) <= in_plane && std::abs(side_q) <= in_plane) return std::nullopt;
  // Which side of the segment's line each triangle edge is: inside when all agree.
  const double wa = SignedVolume(p, q, b, c);
  const double wb = SignedVolume(p, q, c, a);
  const double wc = SignedVolume(p, q, a, b);
  const bool all_non_negative = wa >= 0 && wb >= 0 && wc >= 0;
  const bool all_non_positive = wa <= 0 && wb <= 0 && wc <= 0;
  const double sum = wa + wb + wc;
  if (!(all_non_negative || all_non_positive) || sum == 0) return std::nullopt;
  return SegmentTriangleCrossing{side_p / (side_p - side_q), Eigen::Vector3d(wa, wb, wc) / sum};
}

}  // namespace kerf::geometry
