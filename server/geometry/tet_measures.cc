#include "geometry/tet_measures.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace kerf::geometry {
namespace {

using Eigen::Vector3d;

double AngleBetweenDeg(const Vector3d& u, const Vector3d& v) {
  // atan2 of |u x v| and u.v is accurate near 0 and 180 degrees, unlike acos.
  const double angle = std::atan2(u.cross(v).norm(), u.dot(v));
  return angle * 180.0 / std::numbers::pi;
}

}  // namespace

double SignedVolume(const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& d) {
  return (b - a).cross(c - a).dot(d - a) / 6.0;
}

double SmallestHeight(const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& d) {
  const double twice_largest_face =
      std::max({(c - b).cross(d - b).norm(), (d - a).cross(c - a).norm(),
                (b - a).cross(d - a).norm(), (c - a).cross(b - a).norm()});
  return twice_largest_face > 0 ? 6 * std::abs(SignedVolume(a, b, c, d)) / twice_largest_face : 0;
}

std::array<double, 6> DihedralAnglesDeg(const Vector3d& a, const Vector3d& b, const Vector3d& c,
                                        const Vector3d& d) {
  // Face normals, one per face, each oriented to point away from the corner opposite it.
  // The interior angle at an edge is 180 minus the angle between the
  // outward normals of the two faces meeting there.
  const std::array<Vector3d, 4> p = {a, b, c, d};
  std::array<Vector3d, 4> outward;
  for (int i = 0; i < 4; ++i) {
    const Vector3d& p0 = p[(i + 1) % 4];
    const Vector3d& p1 = p[(i + 2) % 4];
    const Vector3d& p2 = p[(i + 3) % 4];
    Vector3d n = (p1 - p0).cross(p2 - p0);
    if (n.dot(p[i] - p0) > 0) n = -n;
    outward[i] = n;
  }
  // The edge (i, j) is shared by the faces opposite the other two corners k and l.
  constexpr std::array<std::array<int, 4>, 6> kEdges = {
      {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}}};
  std::array<double, 6> angles;
  for (int e = 0; e < 6; ++e) {
    const Vector3d& nk = outward[kEdges[e][2]];
    const Vector3d& nl = outward[kEdges[e][3]];
    angles[e] =
        (nk.squaredNorm() == 0 || nl.squaredNorm() == 0) ? 0.0 : 180.0 - AngleBetweenDeg(nk, nl);
  }
  return angles;
}

double RadiusRatio(const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& d) {
  const double volume = std::abs(SignedVolume(a, b, c, d));
  const double area = 0.5 * ((b - a).cross(c - a).norm() + (b - a).cross(d - a).norm() +
                             (c - a).cross(d - a).norm() + (c - b).cross(d - b).norm());
  if (volume == 0 || area == 0) return 0;
  const double inradius = 3 * volume / area;
  // Circumradius: |sum of |e_i|^2 (e_j x e_k) cyclic| / (12 V), with edges from a.
  const Vector3d u = b - a, v = c - a, w = d - a;
  const Vector3d numerator =
      u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v);
  const double circumradius = numerator.norm() / (12 * volume);
  return 3 * inradius / circumradius;
}

TetMeasures MeasureTet(const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& d) {
  TetMeasures m;
  m.signed_volume = SignedVolume(a, b, c, d);
  const std::array<double, 6> angles = DihedralAnglesDeg(a, b, c, d);
  const auto [lo, hi] = std::minmax_element(angles.begin(), angles.end());
  m.min_dihedral_deg = *lo;
  m.max_dihedral_deg = *hi;
  m.radius_ratio = RadiusRatio(a, b, c, d);
  const std::array<double, 6> lengths = {(b - a).norm(), (c - a).norm(), (d - a).norm(),
                                         (c - b).norm(), (d - b).norm(), (d - c).norm()};
  const auto [short_edge, long_edge] = std::minmax_element(lengths.begin(), lengths.end());
  m.min_edge_length = *short_edge;
  m.max_edge_length = *long_edge;
  return m;
}

bool ContainsPoint(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d, const Eigen::Vector3d& p) {
  const double volume = SignedVolume(a, b, c, d);
  return SignedVolume(p, b, c, d) * volume >= 0 && SignedVolume(a, p, c, d) * volume >= 0 &&
         SignedVolume(a, b, p, d) * volume >= 0 && SignedVolume(a, b, c, p) * volume >= 0;
}

Eigen::Vector4d BarycentricWeights(const Vector3d& a, const Vector3d& b, const Vector3d& c,
                                   const Vector3d& d, const Vector3d& p) {
  Eigen::Matrix3d frame;
  frame << b - a, c - a, d - a;
  const Vector3d w = frame.fullPivLu().solve(p - a);
  return {1 - w.sum(), w.x(), w.y(), w.z()};
}

double SmallestDihedralDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  const std::array<double, 6> angles = DihedralAnglesDeg(a, b, c, d);
  return *std::min_element(angles.begin(), angles.end());
}

double MeanEdgeLength(const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& d) {
  return ((a - b).norm() + (a - c).norm() + (a - d).norm() + (b - c).norm() + (b - d).norm() +
          (c - d).norm()) /
         6;
}

}  // namespace kerf::geometry
