#include "fem/explicit_integrator.h"

#include <cmath>
#include <random>

#include "base/check.h"

namespace kerf::fem {

ExplicitIntegrator::ExplicitIntegrator(const TensorMassModel& model, const BoundaryConditions& bc,
                                       ElasticOptions elastic, std::optional<SleepOptions> sleep)
    : model_(&model), forces_(model, elastic) {
  KERF_CHECK(!sleep.has_value() || elastic.law == ElasticLaw::kLinear);
  if (sleep.has_value()) sleeping_ = std::make_unique<SleepingVertices>(model, *sleep);
  Refresh(bc);
}

void ExplicitIntegrator::Refresh(const BoundaryConditions& bc) {
  const std::size_t n = model_->vertex_count();
  external_ = ExternalForces(bc, model_->masses());
  inverse_mass_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double m = model_->masses()[i];
    inverse_mass_[i] = m > 0 ? 1 / m : 0;
  }
  elastic_.resize(n);
  damped_u_.resize(n);
  prescribed_ = bc.prescribed;
  if (sleeping_ != nullptr) sleeping_->Refresh(bc, external_);
}

void ExplicitIntegrator::Step(double dt, DynamicState* state) {
  const std::size_t n = model_->vertex_count();
  state->displacement.resize(n, Eigen::Vector3d::Zero());
  state->velocity.resize(n, Eigen::Vector3d::Zero());
  const double alpha = model_->material().mass_damping;
  const double beta = model_->material().stiffness_damping;
  // The vertices that move; sleeping ones are held, with zero velocity.
  const std::span<const std::uint32_t> active =
      sleeping_ != nullptr ? sleeping_->awake() : model_->active_vertices();
  forces_.Update(state->displacement);
  const std::vector<Eigen::Vector3d>* w = &state->displacement;  // u + beta v
  if (beta != 0) {
    for (const std::uint32_t i : active) {
      damped_u_[i] = state->displacement[i] + beta * state->velocity[i];
    }
    w = &damped_u_;
  }
  if (sleeping_ == nullptr) {
    forces_.Force(*w, elastic_);
  } else {
    if (beta != 0) {
      for (const std::uint32_t j : sleeping_->border()) damped_u_[j] = state->displacement[j];
    }
    sleeping_->MultiplyStiffness(*w, elastic_);
  }
  const double keep = 1 - dt * alpha;
  for (const std::uint32_t i : active) {
    Eigen::Vector3d& v = state->velocity[i];
    v = keep * v + dt * inverse_mass_[i] * (external_[i] - elastic_[i]);
  }
  for (const PrescribedDisplacement& p : prescribed_) {
    state->velocity[mesh::Index(p.vertex)][p.component] = 0;
    state->displacement[mesh::Index(p.vertex)][p.component] = p.value;
  }
  for (const std::uint32_t i : active) state->displacement[i] += dt * state->velocity[i];
  state->time += dt;
  if (sleeping_ != nullptr) sleeping_->Update(dt, external_, state);
}

double EstimateCriticalTimeStep(const TensorMassModel& model) {
  const std::size_t n = model.vertex_count();
  const std::span<const std::uint32_t> active = model.active_vertices();
  std::vector<Eigen::Vector3d> x(n, Eigen::Vector3d::Zero()), kx(n, Eigen::Vector3d::Zero()),
      y(n, Eigen::Vector3d::Zero());
  std::mt19937 random(3);
  std::uniform_real_distribution<double> uniform(-1, 1);
  for (const std::uint32_t i : active) {
    x[i] = Eigen::Vector3d(uniform(random), uniform(random), uniform(random));
  }
  // Power iteration on the symmetric M^-1/2 K M^-1/2 through y = M^1/2 x, with a Rayleigh
  // quotient for the eigenvalue.
  double eigenvalue = 0;
  for (int iteration = 0; iteration < 500; ++iteration) {
    double norm = 0;
    for (const std::uint32_t i : active) norm += x[i].squaredNorm();
    norm = std::sqrt(norm);
    if (norm == 0) return 0;
    for (const std::uint32_t i : active) {
      x[i] /= norm;
      kx[i] = x[i] / std::sqrt(model.masses()[i]);
    }
    model.MultiplyStiffness(kx, y);
    double rayleigh = 0;
    for (const std::uint32_t i : active) {
      y[i] /= std::sqrt(model.masses()[i]);
      rayleigh += x[i].dot(y[i]);
    }
    std::swap(x, y);
    const bool converged = std::abs(rayleigh - eigenvalue) <= 1e-4 * rayleigh;
    eigenvalue = rayleigh;
    if (converged && iteration > 20) break;
  }
  return eigenvalue > 0 ? 2 / std::sqrt(eigenvalue) : 0;
}

}  // namespace kerf::fem
