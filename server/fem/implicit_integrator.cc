#include "fem/implicit_integrator.h"

#include <Eigen/LU>
#include <cassert>
#include <cmath>
#include <span>

namespace kerf::fem {
namespace {

double Dot(std::span<const std::uint32_t> active, const std::vector<Eigen::Vector3d>& a,
           const std::vector<Eigen::Vector3d>& b) {
  double sum = 0;
  for (const std::uint32_t i : active) sum += a[i].dot(b[i]);
  return sum;
}

}  // namespace

ImplicitIntegrator::ImplicitIntegrator(const TensorMassModel& model, const BoundaryConditions& bc,
                                       ImplicitSolveOptions options)
    : model_(&model), options_(options) {
  assert(options.tolerance > 0 && options.max_iterations > 0);
  Refresh(bc);
}

void ImplicitIntegrator::Refresh(const BoundaryConditions& bc) {
  const std::size_t n = model_->vertex_count();
  external_ = ExternalForces(bc, model_->masses());
  prescribed_ = bc.prescribed;
  free_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    free_[i] = Eigen::Vector3d::Constant(model_->masses()[i] > 0 ? 1 : 0);
  }
  for (const PrescribedDisplacement& p : prescribed_) free_[mesh::Index(p.vertex)][p.component] = 0;
  for (auto* buffer : {&residual_, &direction_, &preconditioned_, &product_, &stiff_}) {
    buffer->resize(n);
  }
  change_.resize(n, Eigen::Vector3d::Zero());
  inverse_diagonal_.resize(n);
  prepared_dt_ = 0;
}

void ImplicitIntegrator::PrepareFor(double dt) {
  if (dt == prepared_dt_) return;
  const Material& material = model_->material();
  const double a = 1 + dt * material.mass_damping;
  const double b = dt * material.stiffness_damping + dt * dt;
  for (const std::uint32_t i : model_->active_vertices()) {
    const Eigen::Matrix3d block = a * model_->masses()[i] * Eigen::Matrix3d::Identity() +
                                  b * model_->vertex_tensor(static_cast<mesh::VertexId>(i));
    inverse_diagonal_[i] = block.inverse();
  }
  prepared_dt_ = dt;
}

void ImplicitIntegrator::MultiplySystem(double a, double b, const std::vector<Eigen::Vector3d>& p,
                                        std::vector<Eigen::Vector3d>* q) {
  model_->MultiplyStiffness(p, stiff_);
  for (const std::uint32_t i : model_->active_vertices()) {
    (*q)[i] = ((a * model_->masses()[i]) * p[i] + b * stiff_[i]).cwiseProduct(free_[i]);
  }
}

void ImplicitIntegrator::Precondition(const std::vector<Eigen::Vector3d>& r,
                                      std::vector<Eigen::Vector3d>* z) const {
  for (const std::uint32_t i : model_->active_vertices()) {
    (*z)[i] = (inverse_diagonal_[i] * r[i]).cwiseProduct(free_[i]);
  }
}

void ImplicitIntegrator::Step(double dt, DynamicState* state) {
  assert(dt > 0);
  const std::size_t n = model_->vertex_count();
  state->displacement.resize(n, Eigen::Vector3d::Zero());
  state->velocity.resize(n, Eigen::Vector3d::Zero());
  PrepareFor(dt);
  const Material& material = model_->material();
  const double a = 1 + dt * material.mass_damping;
  const double b = dt * material.stiffness_damping + dt * dt;
  std::vector<Eigen::Vector3d>& v = state->velocity;
  const std::span<const std::uint32_t> active = model_->active_vertices();

  // The solve starts from g = S (v + change): its residual, for the new velocity, is
  //   S (M v + dt (f - K u) - A g) = S (M (v - a g) + dt f - K (dt u + b g)),
  // one multiply by K. Near equilibrium f and K u cancel, so the tolerance is relative to the
  // size of the terms, not to their sum.
  for (const std::uint32_t i : active) {
    const Eigen::Vector3d old = v[i].cwiseProduct(free_[i]);
    v[i] = (old + change_[i]).cwiseProduct(free_[i]);
    change_[i] = old;  // until the solve is done
    residual_[i] = model_->masses()[i] * (old - a * v[i]);
    product_[i] = dt * state->displacement[i] + b * v[i];
  }
  model_->MultiplyStiffness(product_, stiff_);
  double scale = 0;
  for (const std::uint32_t i : active) {
    residual_[i] = (residual_[i] + dt * external_[i] - stiff_[i]).cwiseProduct(free_[i]);
    const double mass = model_->masses()[i];
    scale += (mass * change_[i].cwiseAbs() + dt * external_[i].cwiseAbs() +
              a * mass * v[i].cwiseAbs() + stiff_[i].cwiseAbs())
                 .cwiseProduct(free_[i])
                 .squaredNorm();
  }
  Precondition(residual_, &preconditioned_);
  for (const std::uint32_t i : active) direction_[i] = preconditioned_[i];
  double rz = Dot(active, residual_, preconditioned_);
  const double goal = options_.tolerance * std::sqrt(scale);
  int iteration = 0;
  double residual_norm = std::sqrt(Dot(active, residual_, residual_));
  while (residual_norm > goal && iteration < options_.max_iterations) {
    MultiplySystem(a, b, direction_, &product_);
    const double curvature = Dot(active, direction_, product_);
    if (!(curvature > 0)) break;  // converged to rounding
    const double step = rz / curvature;
    for (const std::uint32_t i : active) {
      v[i] += step * direction_[i];
      residual_[i] -= step * product_[i];
    }
    Precondition(residual_, &preconditioned_);
    const double rz_next = Dot(active, residual_, preconditioned_);
    const double keep = rz_next / rz;
    for (const std::uint32_t i : active) {
      direction_[i] = preconditioned_[i] + keep * direction_[i];
    }
    rz = rz_next;
    residual_norm = std::sqrt(Dot(active, residual_, residual_));
    ++iteration;
  }
  last_solve_ = {iteration, scale > 0 ? residual_norm / std::sqrt(scale) : 0};

  for (const std::uint32_t i : active) {
    state->displacement[i] += dt * v[i];
    change_[i] = v[i] - change_[i];
  }
  for (const PrescribedDisplacement& p : prescribed_) {
    state->displacement[mesh::Index(p.vertex)][p.component] = p.value;
  }
  state->time += dt;
}

}  // namespace kerf::fem
