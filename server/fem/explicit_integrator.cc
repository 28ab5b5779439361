#include "fem/explicit_integrator.h"

#include <cmath>
#include <random>

namespace kerf::fem {

DynamicState DynamicState::AtRest(const TensorMassModel& model, const BoundaryConditions& bc) {
  DynamicState state;
  state.displacement.assign(model.vertex_count(), Eigen::Vector3d::Zero());
  state.velocity.assign(model.vertex_count(), Eigen::Vector3d::Zero());
  for (const PrescribedDisplacement& p : bc.prescribed) {
    state.displacement[mesh::Index(p.vertex)][p.component] = p.value;
  }
  return state;
}

ExplicitIntegrator::ExplicitIntegrator(const TensorMassModel& model, const BoundaryConditions& bc)
    : model_(&model) {
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
}

void ExplicitIntegrator::Step(double dt, DynamicState* state) {
  const std::size_t n = model_->vertex_count();
  state->displacement.resize(n, Eigen::Vector3d::Zero());
  state->velocity.resize(n, Eigen::Vector3d::Zero());
  const double alpha = model_->material().mass_damping;
  const double beta = model_->material().stiffness_damping;
  if (beta == 0) {
    model_->MultiplyStiffness(state->displacement, elastic_);  // no u + beta v to form
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      damped_u_[i] = state->displacement[i] + beta * state->velocity[i];
    }
    model_->MultiplyStiffness(damped_u_, elastic_);
  }
  const double keep = 1 - dt * alpha;
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Vector3d& v = state->velocity[i];
    v = keep * v + dt * inverse_mass_[i] * (external_[i] - elastic_[i]);
    if (inverse_mass_[i] == 0) v.setZero();
  }
  for (const PrescribedDisplacement& p : prescribed_) {
    state->velocity[mesh::Index(p.vertex)][p.component] = 0;
    state->displacement[mesh::Index(p.vertex)][p.component] = p.value;
  }
  for (std::size_t i = 0; i < n; ++i) state->displacement[i] += dt * state->velocity[i];
  state->time += dt;
}

double MechanicalEnergy(const TensorMassModel& model, const DynamicState& state) {
  double kinetic = 0;
  for (std::size_t i = 0; i < model.vertex_count(); ++i) {
    kinetic += 0.5 * model.masses()[i] * state.velocity[i].squaredNorm();
  }
  return kinetic + model.ElasticEnergy(state.displacement);
}

double EstimateCriticalTimeStep(const TensorMassModel& model) {
  const std::size_t n = model.vertex_count();
  std::vector<Eigen::Vector3d> x(n), kx(n);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> uniform(-1, 1);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = model.masses()[i] > 0
               ? Eigen::Vector3d(uniform(random), uniform(random), uniform(random))
               : Eigen::Vector3d::Zero();
  }
  // Power iteration on the symmetric M^-1/2 K M^-1/2 through y = M^1/2 x, with a Rayleigh
  // quotient for the eigenvalue.
  double eigenvalue = 0;
  for (int iteration = 0; iteration < 500; ++iteration) {
    double norm = 0;
    for (std::size_t i = 0; i < n; ++i) norm += x[i].squaredNorm();
    norm = std::sqrt(norm);
    if (norm == 0) return 0;
    for (std::size_t i = 0; i < n; ++i) {
      x[i] /= norm;
      const double m = model.masses()[i];
      kx[i] = m > 0 ? Eigen::Vector3d(x[i] / std::sqrt(m)) : Eigen::Vector3d::Zero();
    }
    std::vector<Eigen::Vector3d> y(n);
    model.MultiplyStiffness(kx, y);
    double rayleigh = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double m = model.masses()[i];
      y[i] = m > 0 ? Eigen::Vector3d(y[i] / std::sqrt(m)) : Eigen::Vector3d::Zero();
      rayleigh += x[i].dot(y[i]);
    }
    x = std::move(y);
    const bool converged = std::abs(rayleigh - eigenvalue) <= 1e-4 * rayleigh;
    eigenvalue = rayleigh;
    if (converged && iteration > 20) break;
  }
  return eigenvalue > 0 ? 2 / std::sqrt(eigenvalue) : 0;
}

}  // namespace kerf::fem
