// The unit tet, the smallest mesh a cut can be tried on: corners 0 (the origin), 1 (x), 2 (y),
// 3 (z), positively oriented.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>

#include "mesh/tet_mesh.h"

namespace kerf::testing {

inline mesh::TetMesh UnitTet() {
  mesh::TetMesh m;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                   Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 1)}) {
    m.AddVertex(p);
  }
  EXPECT_TRUE(
      m.AddTet({mesh::VertexId(0), mesh::VertexId(1), mesh::VertexId(2), mesh::VertexId(3)}).ok());
  return m;
}

}  // namespace kerf::testing
