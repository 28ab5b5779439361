// The cantilever of ../shared/design/accuracy.md, coarse, for integrator tests.
#pragma once

#include <algorithm>
#include <vector>

#include "fem/boundary_conditions.h"
#include "fem/material.h"
#include "fem/static_solver.h"
#include "fem/time_integrator.h"
#include "mesh/box_lattice.h"

namespace kerf::fem {

struct Cantilever {
  mesh::TetMesh mesh;
  BoundaryConditions bc;
};

// The accuracy.md bar at n = 2, clamped at x = 0, under gravity rho g = 1.
inline Cantilever MakeCantilever() {
  mesh::BoxLatticeSpec spec;
  spec.cells_x = 10;
  spec.cells_y = 2;
  spec.cells_z = 2;
  spec.size = {5, 1, 1};
  Cantilever c{*mesh::MakeBoxLattice(spec), {}};
  c.bc.gravity = {0, 0, -1};
  std::vector<mesh::VertexId> clamped;
  for (const mesh::VertexId v : c.mesh.vertices()) {
    if (c.mesh.rest_position(v).x() == 0) clamped.push_back(v);
  }
  FixVertices(clamped, &c.bc);
  return c;
}

inline Material Accuracy(double mass_damping) {
  Material m;
  m.youngs_modulus = 5000;
  m.poisson_ratio = 0.45;
  m.density = 1;
  m.mass_damping = mass_damping;
  return m;
}

// The bar at rest in its static deflection under `bc`, whose gravity is then taken away: it
// vibrates, undamped if the model's material is.
inline DynamicState ReleasedFromItsDeflection(const TensorMassModel& model,
                                              BoundaryConditions* bc) {
  DynamicState state = DynamicState::AtRest(model, *bc);
  state.displacement = *SolveStaticEquilibrium(model, *bc);
  bc->gravity.setZero();
  return state;
}

inline double MaxNorm(const std::vector<Eigen::Vector3d>& u) {
  double max = 0;
  for (const auto& x : u) max = std::max(max, x.norm());
  return max;
}

}  // namespace kerf::fem
