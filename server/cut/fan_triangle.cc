#include "cut/fan_triangle.h"

namespace kerf::cut {
namespace {

// Barycentric weights lie in the plane where they sum to 1: two of them place a point there.
Eigen::Vector2d InPlane(const Eigen::Vector3d& w) { return {w[1], w[2]}; }

double Cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  return u.x() * v.y() - u.y() * v.x();
}

}  // namespace

std::optional<int> FanTriangleHolding(std::span<const Eigen::Vector3d> boundary,
                                      const Eigen::Vector3d& hub, const Eigen::Vector3d& point,
                                      double margin) {
  const Eigen::Vector2d a = InPlane(hub), p = InPlane(point);
  const int n = static_cast<int>(boundary.size());
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d b = InPlane(boundary[i]), c = InPlane(boundary[(i + 1) % n]);
    const double area = Cross(b - a, c - a);
    if (area == 0) continue;
    const double s = Cross(p - a, c - a) / area, t = Cross(b - a, p - a) / area;
    if (s >= margin && t >= margin && 1 - s - t >= margin) return i;
  }
  return std::nullopt;
}

}  // namespace kerf::cut
