// Measures of a single tetrahedron given its four corner positions (a, b, c, d).
//
// Lengths are in the caller's length unit, volumes in its cube, angles in degrees.
// A tet is positively oriented when d lies on the side of triangle (a, b, c) that its
// right-hand normal (b - a) x (c - a) points to; then SignedVolume > 0.
#pragma once

#include <Eigen/Core>
#include <array>

namespace kerf::geometry {

// Signed volume: ((b - a) x (c - a)) . (d - a) / 6. Positive for a positively oriented tet.
double SignedVolume(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& d);

// Whether p lies inside the tet (a, b, c, d) or on its boundary, whatever its orientation:
// replacing any corner by p does not flip the sign of the volume.
bool ContainsPoint(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d, const Eigen::Vector3d& p);

// The barycentric weights of `p` on the corners (a, b, c, d): summing to 1, all in [0, 1] for a
// point inside, the point itself being sum w_k x_k. The tet must not be flat.
Eigen::Vector4d BarycentricWeights(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c, const Eigen::Vector3d& d,
                                   const Eigen::Vector3d& p);

// The six interior dihedral angles, in degrees, at edges ab, ac, ad, bc, bd, cd.
// A degenerate (flat) tet has angles of 0 or 180; a zero-area face gives NaN-free 0.
std::array<double, 6> DihedralAnglesDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                        const Eigen::Vector3d& c, const Eigen::Vector3d& d);
// The smallest of them.
double SmallestDihedralDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c, const Eigen::Vector3d& d);

// The mean of the six edges' lengths (edges ab, ac, ad, bc, bd, cd summed in that order).
double MeanEdgeLength(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                      const Eigen::Vector3d& d);

// The smallest of the four heights (corner to opposite face's plane): three times the volume
// over the largest face's area; 0 for a flat tet. The explicit time step scales with it.
double SmallestHeight(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                      const Eigen::Vector3d& d);

// 3 * inradius / circumradius: 1 for the regular tet, 0 for a flat one. Orientation-free.
double RadiusRatio(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d);

// Everything a quality report needs about one tet, computed together.
struct TetMeasures {
  double signed_volume = 0;
  double min_dihedral_deg = 0;
  double max_dihedral_deg = 0;
  double radius_ratio = 0;
  double min_edge_length = 0;
  double max_edge_length = 0;
};

TetMeasures MeasureTet(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                       const Eigen::Vector3d& d);

}  // namespace kerf::geometry
