#include "fem/implicit_integrator.h"

#include <Eigen/LU>
#include <cmath>
#include <span>

#include "base/check.h"

namespace kerf::fem {
ImplicitIntegrator::ImplicitIntegrator(const TensorMassModel& model, const BoundaryConditions& bc,
                                       ImplicitSolveOptions options, ElasticOptions elastic,
                                       std::optional<SleepOptions> sleep)
    : model_(&model), options_(options), forces_(model, elastic) {
  KERF_CHECK(options.tolerance > 0 && options.max_iterations > 0);
  KERF_CHECK(!sleep.has_value() || elastic.law == ElasticLaw::kLinear);
  if (sleep.has_value()) sleeping_ = std::make_unique<SleepingVertices>(model, *sleep);
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
  if (sleeping_ != nullptr) sleeping_->Refresh(bc, external_);
}

void ImplicitIntegrator::PrepareFor(double dt) {
  if (dt == prepared_dt_) return;
  const Material& material = model_->material();
  const double a = 1 + dt * material.mass_damping;
  const double b = dt * material.stiffness_damping + dt * dt;
  if (forces_.rotating()) forces_.DiagonalBlocks(inverse_diagonal_);
  for (const std::uint32_t i : Moving()) {
    const Eigen::Matrix3d& k_ii = forces_.rotating()
                                      ? inverse_diagonal_[i]
                                      : model_->vertex_tensor(static_cast<mesh::VertexId>(i));
    const Eigen::Matrix3d block = a * model_->masses()[i] * Eigen::Matrix3d::Identity() + b * k_ii;
    inverse_diagonal_[i] = block.inverse();
  }
  prepared_dt_ = dt;
}

void ImplicitIntegrator::Force(const std::vector<Eigen::Vector3d>& w,
                               std::vector<Eigen::Vector3d>* f) const {
  if (sleeping_ == nullptr) {
    forces_.Force(w, *f);
  } else {
    sleeping_->MultiplyStiffness(w, *f);
  }
}

double ImplicitIntegrator::MultiplySystem(double a, double b, const std::vector<Eigen::Vector3d>& p,
                                          std::vector<Eigen::Vector3d>* q) {
  // Linear in p: the force law's force without its rest-shape term.
  if (sleeping_ == nullptr) {
    forces_.Multiply(p, stiff_);
  } else {
    Force(p, &stiff_);
  }
  double pq = 0;
  for (const std::uint32_t i : Moving()) {
    (*q)[i] = ((a * model_->masses()[i]) * p[i] + b * stiff_[i]).cwiseProduct(free_[i]);
    pq += p[i].dot((*q)[i]);
  }
  return pq;
}

void ImplicitIntegrator::Step(double dt, DynamicState* state) {
  KERF_CHECK(dt > 0);
  const std::size_t n = model_->vertex_count();
  state->displacement.resize(n, Eigen::Vector3d::Zero());
  state->velocity.resize(n, Eigen::Vector3d::Zero());
  forces_.Update(state->displacement);
  if (forces_.rotating()) prepared_dt_ = 0;  // the diagonal blocks turned
  PrepareFor(dt);
  const Material& material = model_->material();
  const double a = 1 + dt * material.mass_damping;
  const double b = dt * material.stiffness_damping + dt * dt;
  std::vector<Eigen::Vector3d>& v = state->velocity;
  const std::span<const std::uint32_t> active = Moving();
  if (sleeping_ != nullptr) {
    // The awake rows read their sleeping neighbours: held (zero velocity and direction).
    for (const std::uint32_t j : sleeping_->border()) {
      product_[j] = state->displacement[j];
      direction_[j].setZero();
    }
  }

  // The solve starts from g = S (v + change): its residual, for the new velocity, is
  //   S (M v + dt (f - K u) - A g) = S (M (v - a g) + dt f - dt K (u + (b / dt) g)),
  // one force evaluation (affine in its argument when rotating, so that form adds b K g and
  // dt times the force at u). Near equilibrium f and K u cancel, so the tolerance is relative
  // to the size of the terms, not to their sum.
  for (const std::uint32_t i : active) {
    const Eigen::Vector3d old = v[i].cwiseProduct(free_[i]);
    v[i] = (old + change_[i]).cwiseProduct(free_[i]);
    change_[i] = old;  // until the solve is done
    residual_[i] = model_->masses()[i] * (old - a * v[i]);
    product_[i] = state->displacement[i] + (b / dt) * v[i];
  }
  Force(product_, &stiff_);
  double scale = 0;
  for (const std::uint32_t i : active) {
    stiff_[i] *= dt;
    residual_[i] = (residual_[i] + dt * external_[i] - stiff_[i]).cwiseProduct(free_[i]);
    const double mass = model_->masses()[i];
    scale += (mass * change_[i].cwiseAbs() + dt * external_[i].cwiseAbs() +
              a * mass * v[i].cwiseAbs() + stiff_[i].cwiseAbs())
                 .cwiseProduct(free_[i])
                 .squaredNorm();
  }
  double rz = 0, rr = 0;
  for (const std::uint32_t i : active) {
    direction_[i] = Precondition(i, residual_[i]);
    rz += residual_[i].dot(direction_[i]);
    rr += residual_[i].squaredNorm();
  }
  const double goal = options_.tolerance * std::sqrt(scale);
  int iteration = 0;
  while (std::sqrt(rr) > goal && iteration < options_.max_iterations) {
    const double curvature = MultiplySystem(a, b, direction_, &product_);
    if (!(curvature > 0)) break;  // converged to rounding
    const double step = rz / curvature;
    double rz_next = 0;
    rr = 0;
    for (const std::uint32_t i : active) {
      v[i] += step * direction_[i];
      residual_[i] -= step * product_[i];
      preconditioned_[i] = Precondition(i, residual_[i]);
      rz_next += residual_[i].dot(preconditioned_[i]);
      rr += residual_[i].squaredNorm();
    }
    const double keep = rz_next / rz;
    for (const std::uint32_t i : active) {
      direction_[i] = preconditioned_[i] + keep * direction_[i];
    }
    rz = rz_next;
    ++iteration;
  }
  const double residual_norm = std::sqrt(rr);
  last_solve_ = {iteration, scale > 0 ? residual_norm / std::sqrt(scale) : 0};

  for (const std::uint32_t i : active) {
    state->displacement[i] += dt * v[i];
    change_[i] = v[i] - change_[i];
  }
  for (const PrescribedDisplacement& p : prescribed_) {
    state->displacement[mesh::Index(p.vertex)][p.component] = p.value;
  }
  state->time += dt;
  if (sleeping_ != nullptr) {
    sleeping_->Update(dt, external_, state);
    if (sleeping_->changed()) prepared_dt_ = 0;  // woken vertices need their blocks
  }
}

}  // namespace kerf::fem
