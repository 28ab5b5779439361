// Explicit time integration of M a = f_external - K u - C v with lumped mass and Rayleigh
// damping C = alpha M + beta K, by symplectic (semi-implicit) Euler:
//   v <- v + dt M^-1 (f_external - K (u + beta v)) - dt alpha v,   u <- u + dt v.
// Stable for dt < 2 / omega_max (undamped), omega_max^2 the largest eigenvalue of M^-1 K.
#pragma once

#include <vector>

#include "fem/boundary_conditions.h"
#include "fem/tensor_mass_model.h"

namespace kerf::fem {

// Displacement and velocity of every vertex, indexed by vertex index.
struct DynamicState {
  std::vector<Eigen::Vector3d> displacement;
  std::vector<Eigen::Vector3d> velocity;
  double time = 0;

  // Zero displacement and velocity for every vertex of the model, with prescribed components
  // at their values.
  static DynamicState AtRest(const TensorMassModel& model, const BoundaryConditions& bc);
};

// Reusable buffers so that a step allocates nothing.
class ExplicitIntegrator {
 public:
  // bc must be valid for the model's mesh (see ValidateBoundaryConditions).
  ExplicitIntegrator(const TensorMassModel& model, const BoundaryConditions& bc);

  // One step of dt (s). Prescribed components keep their values and zero velocity; vertices
  // with no mass (used by no tet) do not move. O(vertices + edges).
  void Step(double dt, DynamicState* state);

  // Rebuilds what depends on the model's mass or the conditions (after the model synced
  // with a changed mesh).
  void Refresh(const BoundaryConditions& bc);

 private:
  const TensorMassModel* model_;
  std::vector<Eigen::Vector3d> external_;
  std::vector<double> inverse_mass_;
  std::vector<Eigen::Vector3d> elastic_;   // K (u + beta v)
  std::vector<Eigen::Vector3d> damped_u_;  // u + beta v
  std::vector<PrescribedDisplacement> prescribed_;
};

// Kinetic energy v^T M v / 2 plus elastic energy u^T K u / 2.
double MechanicalEnergy(const TensorMassModel& model, const DynamicState& state);

// The largest stable symplectic-Euler step 2 / omega_max, omega_max^2 the largest eigenvalue
// of M^-1 K, by power iteration (relative accuracy ~1e-3, iterations capped at 500).
// Prescribed components are not excluded, which can only make the estimate smaller (safer).
double EstimateCriticalTimeStep(const TensorMassModel& model);

}  // namespace kerf::fem
