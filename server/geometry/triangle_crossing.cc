#include "geometry/triangle_crossing.h"

#include <vector>

#include "geometry/segment_triangle_intersection.h"

namespace kerf::geometry {

std::optional<std::array<Eigen::Vector3d, 2>> TrianglesCross(
    const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
    const Eigen::Vector3d& d, const Eigen::Vector3d& e, const Eigen::Vector3d& f) {
  // The segment's ends are where edges of one triangle cross the other.
  const std::array<Eigen::Vector3d, 3> one = {a, b, c}, other = {d, e, f};
  std::vector<Eigen::Vector3d> ends;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d &p = one[k], &q = one[(k + 1) % 3];
    if (const auto x = IntersectSegmentTriangle(p, q, d, e, f)) ends.push_back(p + x->t * (q - p));
    const Eigen::Vector3d &r = other[k], &s = other[(k + 1) % 3];
    if (const auto x = IntersectSegmentTriangle(r, s, a, b, c)) ends.push_back(r + x->t * (s - r));
  }
  if (ends.empty()) return std::nullopt;
  // The farthest apart (a crossing through a corner is found on both of its edges).
  std::array<Eigen::Vector3d, 2> farthest = {ends[0], ends[0]};
  double apart = 0;
  for (std::size_t i = 0; i < ends.size(); ++i) {
    for (std::size_t j = i + 1; j < ends.size(); ++j) {
      const double d2 = (ends[i] - ends[j]).squaredNorm();
      if (d2 > apart) apart = d2, farthest = {ends[i], ends[j]};
    }
  }
  return farthest;
}

}  // namespace kerf::geometry
