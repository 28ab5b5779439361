// Symplectic Euler in sub-steps: each step is split into the fewest equal sub-steps that are
// each at most a fraction of the critical step, bounded again whenever the model changed (a
// cut). Explicit integration that keeps the caller's rate (1 ms, the haptic loop) however
// small the elements a cut makes, paying for them in sub-steps.
#pragma once

#include "fem/explicit_integrator.h"

namespace kerf::fem {

// The largest step symplectic Euler is sure to be stable at: 2 / sqrt(g), g Gershgorin's
// bound on the largest eigenvalue of M^-1/2 K M^-1/2 (the largest row sum of its absolute
// entries), so never above EstimateCriticalTimeStep's answer. One pass over the vertex and edge
// tensors: O(active vertices + edges), about one multiply by K. 0 for a model with no stiffness.
// For the corotational law it bounds the linear K, whose element matrices have the same
// eigenvalues as the rotated ones.
double BoundCriticalTimeStep(const TensorMassModel& model);

class SubsteppedIntegrator : public TimeIntegrator {
 public:
  // fraction in (0, 1]: each sub-step is at most this share of BoundCriticalTimeStep.
  SubsteppedIntegrator(const TensorMassModel& model, const BoundaryConditions& bc,
                       ElasticOptions elastic = {}, double fraction = kDefaultFraction);

  // ceil(dt / (fraction x bound)) sub-steps of symplectic Euler. O(sub-steps x (active
  // vertices + edges)), plus the bound after a Refresh.
  void Step(double dt, DynamicState* state) override;
  // Also bounds the critical step again at the next Step (the model changed).
  void Refresh(const BoundaryConditions& bc) override;
  const ElasticForces& elastic_forces() const override { return steps_.elastic_forces(); }

  int last_sub_steps() const { return last_sub_steps_; }
  // The bound in use (s); 0 until the first Step.
  double critical_time_step_bound() const { return bound_; }

  static constexpr double kDefaultFraction = 0.9;

 private:
  const TensorMassModel* model_;
  ExplicitIntegrator steps_;
  double fraction_;
  double bound_ = 0;
  bool stale_ = true;
  int last_sub_steps_ = 0;
};

}  // namespace kerf::fem
