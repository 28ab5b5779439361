// Implicit time integration by backward Euler, with lumped mass and Rayleigh damping
// C = alpha M + beta K:
//   (M + dt C + dt^2 K) v' = M v + dt (f_external - K u),   u' = u + dt v'.
// Unconditionally stable: for a fixed model and no external force, the mechanical energy
// never grows, whatever dt and however small the smallest element. Each step loses
// (|v' - v|_M^2 + |u' - u|_K^2) / 2 of it, even undamped: backward Euler damps the modes
// above about 1 / dt. So the model may change between steps (cuts) with no new step
// estimate.
//
// The system is solved by conjugate gradients on the model's own tensors, which the model
// updates incrementally after cuts (never assembled, never factorised), preconditioned by the
// inverse of each vertex's 3x3 diagonal block and started from the velocity the last step's
// change predicts (v + (v - v_previous)).
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "fem/sleeping_vertices.h"
#include "fem/time_integrator.h"

namespace kerf::fem {

struct ImplicitSolveOptions {
  // The solve stops when |residual| <= tolerance |terms| (Euclidean, over the free
  // components; the terms of the momentum balance M v + dt f_external = a M g + K (dt u + b g)
  // at the solve's start g, a = 1 + dt alpha, b = dt beta + dt^2, taken apart, since near
  // equilibrium they cancel) ...
  double tolerance = 1e-6;
  // ... or after this many iterations (each one multiply by K).
  int max_iterations = 1000;
};

// How the last step's linear solve went.
struct ImplicitSolveReport {
  int iterations = 0;
  double relative_residual = 0;  // |residual| / |terms|
};

// Reusable buffers so that a step allocates nothing once the mesh stops growing.
class ImplicitIntegrator : public TimeIntegrator {
 public:
  // bc must be valid for the model's mesh (see ValidateBoundaryConditions). With `sleep`,
  // vertices at rest sleep (the linear law only): the solve is for the awake vertices, the
  // sleeping ones held.
  ImplicitIntegrator(const TensorMassModel& model, const BoundaryConditions& bc,
                     ImplicitSolveOptions options = {}, ElasticOptions elastic = {},
                     std::optional<SleepOptions> sleep = {});

  // O((active vertices + edges) x iterations); sleeping, O((awake vertices and their edges)
  // x iterations).
  void Step(double dt, DynamicState* state) override;
  void Refresh(const BoundaryConditions& bc) override;
  const ElasticForces& elastic_forces() const override { return forces_; }
  void WakeAll() override {
    if (sleeping_ != nullptr) sleeping_->WakeAll();
  }
  const SleepingVertices* sleeping() const override { return sleeping_.get(); }

  const ImplicitSolveReport& last_solve() const { return last_solve_; }

 private:
  // The vertices that move: the active ones, or the awake ones.
  std::span<const std::uint32_t> Moving() const {
    return sleeping_ != nullptr ? sleeping_->awake() : model_->active_vertices();
  }
  // f = K w (by the law) at the moving vertices.
  void Force(const std::vector<Eigen::Vector3d>& w, std::vector<Eigen::Vector3d>* f) const;
  // q = S (a M + b K) p, S zeroing the components that do not move; returns p . q.
  double MultiplySystem(double a, double b, const std::vector<Eigen::Vector3d>& p,
                        std::vector<Eigen::Vector3d>* q);
  // z = S P^-1 r at vertex i, P the system's 3x3 diagonal blocks.
  Eigen::Vector3d Precondition(std::uint32_t i, const Eigen::Vector3d& r) const {
    return (inverse_diagonal_[i] * r).cwiseProduct(free_[i]);
  }
  void PrepareFor(double dt);

  const TensorMassModel* model_;
  ImplicitSolveOptions options_;
  ElasticForces forces_;
  std::vector<Eigen::Vector3d> external_;
  std::vector<PrescribedDisplacement> prescribed_;
  std::vector<Eigen::Vector3d> free_;  // per component: 1 if it moves, 0 if held or massless
  std::vector<Eigen::Matrix3d> inverse_diagonal_;
  // The dt inverse_diagonal_ is for (at the moving vertices); 0 after a refresh, a rotation
  // or a vertex woken.
  double prepared_dt_ = 0;
  std::vector<Eigen::Vector3d> residual_, direction_, preconditioned_, product_, stiff_;
  // v' - v of the last step (zero for vertices it did not move): the next solve starts from
  // v + change_.
  std::vector<Eigen::Vector3d> change_;
  ImplicitSolveReport last_solve_;
  std::unique_ptr<SleepingVertices> sleeping_;
};

}  // namespace kerf::fem
