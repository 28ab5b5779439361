// Finding mesh elements by where they are, for tests that should not depend on numbering.
#pragma once

#include <Eigen/Core>

#include "mesh/tet_mesh.h"

namespace kerf::testing {

// The live vertex whose rest position is exactly `p` (asserted to exist).
inline mesh::VertexId VertexAt(const mesh::TetMesh& m, const Eigen::Vector3d& p) {
  for (const mesh::VertexId v : m.vertices()) {
    if (m.rest_position(v) == p) return v;
  }
  ADD_FAILURE() << "no vertex at " << p.transpose();
  return mesh::VertexId{0};
}

// A live tet whose rest centroid lies in the box [low, high].
inline mesh::TetId TetWithCentroidIn(const mesh::TetMesh& m, const Eigen::Vector3d& low,
                                     const Eigen::Vector3d& high) {
  for (const mesh::TetId t : m.tets()) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const mesh::VertexId v : m.tet(t)) c += 0.25 * m.rest_position(v);
    if ((c.array() >= low.array()).all() && (c.array() <= high.array()).all()) return t;
  }
  ADD_FAILURE() << "no tet with its centroid in the box";
  return mesh::TetId{0};
}

}  // namespace kerf::testing
