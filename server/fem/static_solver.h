// Static equilibrium of the linear model: K u = f_external with prescribed components held.
// For verification against a trusted solver and for initial states.
#pragma once

#include <vector>

#include "absl/status/statusor.h"
#include "fem/boundary_conditions.h"
#include "fem/tensor_mass_model.h"

namespace kerf::fem {

// The displacement of every vertex (indexed by vertex index; zero for vertices no tet uses).
// Solved with a sparse Cholesky (LDL^T) factorisation of the free part of K.
// INVALID_ARGUMENT for bad boundary conditions; FAILED_PRECONDITION if the body can still
// move rigidly (K singular on the free components).
absl::StatusOr<std::vector<Eigen::Vector3d>> SolveStaticEquilibrium(const TensorMassModel& model,
                                                                    const BoundaryConditions& bc);

}  // namespace kerf::fem
