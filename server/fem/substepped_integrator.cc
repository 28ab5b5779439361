#include "fem/substepped_integrator.h"

#include <algorithm>
#include <cmath>

#include "base/check.h"

namespace kerf::fem {

double BoundCriticalTimeStep(const TensorMassModel& model) {
  const std::span<const double> mass = model.masses();
  std::vector<Eigen::Vector3d> row_sums(model.vertex_count(), Eigen::Vector3d::Zero());
  for (const std::uint32_t i : model.active_vertices()) {
    row_sums[i] =
        model.vertex_tensor(static_cast<mesh::VertexId>(i)).cwiseAbs().rowwise().sum() / mass[i];
  }
  for (const EdgeTensor& e : model.edges()) {
    const std::uint32_t a = mesh::Index(e.a), b = mesh::Index(e.b);
    if (mass[a] <= 0 || mass[b] <= 0) continue;
    const double scale = 1 / std::sqrt(mass[a] * mass[b]);
    row_sums[a] += scale * e.k_ab.cwiseAbs().rowwise().sum();
    row_sums[b] += scale * e.k_ab.cwiseAbs().colwise().sum().transpose();
  }
  double largest = 0;
  for (const std::uint32_t i : model.active_vertices()) {
    largest = std::max(largest, row_sums[i].maxCoeff());
  }
  return largest > 0 ? 2 / std::sqrt(largest) : 0;
}

SubsteppedIntegrator::SubsteppedIntegrator(const TensorMassModel& model,
                                           const BoundaryConditions& bc, ElasticOptions elastic,
                                           double fraction)
    : model_(&model), steps_(model, bc, elastic), fraction_(fraction) {
  KERF_CHECK(fraction > 0 && fraction <= 1);
}

void SubsteppedIntegrator::Refresh(const BoundaryConditions& bc) {
  steps_.Refresh(bc);
  stale_ = true;
}

void SubsteppedIntegrator::Step(double dt, DynamicState* state) {
  KERF_CHECK(dt > 0);
  if (stale_) {
    bound_ = BoundCriticalTimeStep(*model_);
    stale_ = false;
  }
  const double largest = fraction_ * bound_;
  last_sub_steps_ = largest > 0 ? std::max(1, static_cast<int>(std::ceil(dt / largest))) : 1;
  const double sub_step = dt / last_sub_steps_;
  for (int s = 0; s < last_sub_steps_; ++s) steps_.Step(sub_step, state);
}

}  // namespace kerf::fem
