// What a time integrator advances, and the interface the simulation steps it through.
#pragma once

#include <vector>

#include "fem/boundary_conditions.h"
#include "fem/elastic_forces.h"
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

// Kinetic energy v^T M v / 2 plus elastic energy u^T K u / 2, or that of `forces`' law (see
// ElasticForces::Energy).
double MechanicalEnergy(const TensorMassModel& model, const DynamicState& state,
                        const ElasticForces* forces = nullptr);

// Integrates M a = f_external - K u - C v for a TensorMassModel, with lumped mass and Rayleigh
// damping C = alpha M + beta K. Prescribed components keep their values and zero velocity;
// vertices with no mass (used by no tet) do not move.
class SleepingVertices;

class TimeIntegrator {
 public:
  virtual ~TimeIntegrator() = default;
  // One step of dt (s). The state grows to the model's vertex count (new vertices at rest).
  virtual void Step(double dt, DynamicState* state) = 0;
  // Rebuilds what depends on the model's mass or the conditions (after the model synced
  // with a changed mesh). bc must be valid for the model's mesh.
  virtual void Refresh(const BoundaryConditions& bc) = 0;
  // The force law it steps, with the rotations of its last step.
  virtual const ElasticForces& elastic_forces() const = 0;
  // The state was set from outside: every vertex moves again.
  virtual void WakeAll() {}
  // The vertices it lets sleep (see fem::SleepingVertices), or null if every vertex moves.
  virtual const SleepingVertices* sleeping() const { return nullptr; }
};

}  // namespace kerf::fem
