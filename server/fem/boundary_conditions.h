// What holds and loads a body: prescribed displacement components, gravity and nodal loads.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "absl/status/status.h"
#include "mesh/tet_mesh.h"

namespace kerf::fem {

// One displacement component of one vertex held at a value (0 fixes it; non-zero puts the
// body under tension or compression, as in the paper's Figure 7).
struct PrescribedDisplacement {
  mesh::VertexId vertex;
  int component;  // 0, 1, 2 for x, y, z
  double value;   // in length units
};

struct NodalLoad {
  mesh::VertexId vertex;
  Eigen::Vector3d force;  // in N
};

struct BoundaryConditions {
  std::vector<PrescribedDisplacement> prescribed;
  std::vector<NodalLoad> loads;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  // acceleration, in m/s^2
};

// OK, or INVALID_ARGUMENT naming the first entry that is not on a live vertex, has a
// component outside 0..2, or is not finite.
absl::Status ValidateBoundaryConditions(const mesh::TetMesh& mesh, const BoundaryConditions& bc);

// Holds all three components of each vertex at zero.
void FixVertices(const std::vector<mesh::VertexId>& vertices, BoundaryConditions* bc);

// The external force on each vertex (indexed by vertex index): loads plus mass times gravity.
std::vector<Eigen::Vector3d> ExternalForces(const BoundaryConditions& bc,
                                            std::span<const double> masses);

}  // namespace kerf::fem
