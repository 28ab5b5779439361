// Quality measures of a whole mesh, on its rest shape.
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include "absl/base/attributes.h"
#include "mesh/tet_mesh.h"

namespace kerf::mesh {

// A tet whose smallest dihedral angle is under this is a sliver: it makes explicit time
// steps tiny and stiffness ill-conditioned.
inline constexpr double kDefaultSliverAngleDeg = 5.0;

struct MeshQuality {
  std::size_t tets = 0;
  double total_volume = 0;  // sum of signed rest volumes
  double min_volume = 0;
  double max_volume = 0;
  double min_edge_length = 0;
  double max_edge_length = 0;
  double min_dihedral_deg = 0;
  double max_dihedral_deg = 0;
  double min_radius_ratio = 0;
  double mean_radius_ratio = 0;
  std::size_t slivers = 0;  // tets with min dihedral under the sliver angle
  // Tets by their smallest dihedral angle, in 10-degree bins: [0,10), [10,20), ... [70,80].
  // (The largest possible smallest angle, of the regular tet, is 70.53 degrees.)
  std::array<std::size_t, 8> min_dihedral_histogram{};
};

// The smallest box holding the live vertices, on rest or current positions; zero for an
// empty mesh. O(vertices).
struct Bounds {
  Eigen::Vector3d low = Eigen::Vector3d::Zero();
  Eigen::Vector3d high = Eigen::Vector3d::Zero();
  double diagonal() const { return (high - low).norm(); }
};
Bounds MeasureBounds(const TetMesh& mesh, bool current = false);
// The same for the corners of one live tet. O(1); always inline, as grid queries call it for every
// tet they return (the tet is checked alive, its corners are then), and a large unity build's
// inlining budget can leave it a call (1% more instructions a progressive pose).
ABSL_ATTRIBUTE_ALWAYS_INLINE inline Bounds MeasureTetBounds(const TetMesh& mesh, TetId t,
                                                            bool current = false) {
  const std::span<const Eigen::Vector3d> x =
      current ? mesh.current_positions() : mesh.rest_positions();
  const TetVertices& v = mesh.tet(t);
  const Eigen::Vector3d& a = x[Index(v[0])];
  const Eigen::Vector3d& b = x[Index(v[1])];
  const Eigen::Vector3d& c = x[Index(v[2])];
  const Eigen::Vector3d& d = x[Index(v[3])];
  return {a.cwiseMin(b).cwiseMin(c.cwiseMin(d)), a.cwiseMax(b).cwiseMax(c.cwiseMax(d))};
}

// The mean length of the live tets' edges (each counted once per tet), on current
// positions; 0 for a mesh with no tets. O(tets).
double MeanEdgeLength(const TetMesh& mesh);

// Measures every live tet on rest positions. All fields are zero for a mesh with no tets.
// O(tets).
MeshQuality MeasureMeshQuality(const TetMesh& mesh,
                               double sliver_angle_deg = kDefaultSliverAngleDeg);

}  // namespace kerf::mesh
