// Explicit time integration of M a = f_external - K u - C v with lumped mass and Rayleigh
// damping C = alpha M + beta K, by symplectic (semi-implicit) Euler:
//   v <- v + dt M^-1 (f_external - K (u + beta v)) - dt alpha v,   u <- u + dt v,
// K u the elastic force of the chosen law (fem::ElasticForces; rotations taken from u).
// Stable for dt < 2 / omega_max (undamped), omega_max^2 the largest eigenvalue of M^-1 K.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "fem/elastic_forces.h"
#include "fem/sleeping_vertices.h"
#include "fem/time_integrator.h"

namespace kerf::fem {

// Reusable buffers so that a step allocates nothing.
class ExplicitIntegrator : public TimeIntegrator {
 public:
  // bc must be valid for the model's mesh (see ValidateBoundaryConditions). With `sleep`,
  // vertices at rest sleep (the linear law only).
  ExplicitIntegrator(const TensorMassModel& model, const BoundaryConditions& bc,
                     ElasticOptions elastic = {}, std::optional<SleepOptions> sleep = {});

  // O(active vertices + edges), plus O(tets) for a rotating law; sleeping, O(awake vertices
  // and their edges).
  void Step(double dt, DynamicState* state) override;
  void Refresh(const BoundaryConditions& bc) override;
  const ElasticForces& elastic_forces() const override { return forces_; }
  void WakeAll() override {
    if (sleeping_ != nullptr) sleeping_->WakeAll();
  }
  const SleepingVertices* sleeping() const override { return sleeping_.get(); }

 private:
  const TensorMassModel* model_;
  ElasticForces forces_;
  std::vector<Eigen::Vector3d> external_;
  std::vector<double> inverse_mass_;
  std::vector<Eigen::Vector3d> elastic_;   // K (u + beta v)
  std::vector<Eigen::Vector3d> damped_u_;  // u + beta v
  std::vector<PrescribedDisplacement> prescribed_;
  std::unique_ptr<SleepingVertices> sleeping_;
};

// The largest stable symplectic-Euler step 2 / omega_max, omega_max^2 the largest eigenvalue
// of M^-1 K, by power iteration (relative accuracy ~1e-3, iterations capped at 500).
// Prescribed components are not excluded, which can only make the estimate smaller (safer).
double EstimateCriticalTimeStep(const TensorMassModel& model);

}  // namespace kerf::fem
