#include "fem/boundary_conditions.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace kerf::fem {

absl::Status ValidateBoundaryConditions(const mesh::TetMesh& mesh, const BoundaryConditions& bc) {
  for (std::size_t i = 0; i < bc.prescribed.size(); ++i) {
    const PrescribedDisplacement& p = bc.prescribed[i];
    if (!mesh.IsAlive(p.vertex)) {
      return absl::InvalidArgumentError(absl::StrCat("prescribed displacement ", i, ": vertex ",
                                                     mesh::Index(p.vertex), " is not alive"));
    }
    if (p.component < 0 || p.component > 2 || !std::isfinite(p.value)) {
      return absl::InvalidArgumentError(absl::StrCat("prescribed displacement ", i, ": component ",
                                                     p.component, " value ", p.value,
                                                     " (need 0..2 and finite)"));
    }
  }
  for (std::size_t i = 0; i < bc.loads.size(); ++i) {
    if (!mesh.IsAlive(bc.loads[i].vertex) || !bc.loads[i].force.allFinite()) {
      return absl::InvalidArgumentError(absl::StrCat("nodal load ", i, " on vertex ",
                                                     mesh::Index(bc.loads[i].vertex),
                                                     ": need a live vertex and a finite force"));
    }
  }
  if (!bc.gravity.allFinite()) return absl::InvalidArgumentError("gravity must be finite");
  return absl::OkStatus();
}

void FixVertices(const std::vector<mesh::VertexId>& vertices, BoundaryConditions* bc) {
  for (const mesh::VertexId v : vertices) {
    for (int c = 0; c < 3; ++c) bc->prescribed.push_back({v, c, 0.0});
  }
}

std::vector<Eigen::Vector3d> ExternalForces(const BoundaryConditions& bc,
                                            std::span<const double> masses) {
  std::vector<Eigen::Vector3d> f(masses.size());
  for (std::size_t i = 0; i < masses.size(); ++i) f[i] = masses[i] * bc.gravity;
  for (const NodalLoad& load : bc.loads) f[mesh::Index(load.vertex)] += load.force;
  return f;
}

}  // namespace kerf::fem
