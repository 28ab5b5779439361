// A running scene: its mesh, the tensor-mass model that follows it, and the dynamic state,
// advanced one time step at a time. What the command line runs headless and what a service
// session will step.
#pragma once

#include <memory>

#include "absl/status/statusor.h"
#include "cut/crack_cutter.h"
#include "fem/implicit_integrator.h"
#include "fem/substepped_integrator.h"
#include "fem/tensor_mass_model.h"
#include "fem/time_integrator.h"
#include "sim/scene.h"

namespace kerf::sim {

class Simulation {
 public:
  // INVALID_ARGUMENT for a scene whose stiffness cannot be built (a flat tet) or whose
  // conditions do not fit its mesh; FAILED_PRECONDITION for a STATIC scene that is not held.
  static absl::StatusOr<std::unique_ptr<Simulation>> Create(Scene scene);

  // Advances by time_step() (SYMPLECTIC_EULER, IMPLICIT_EULER), or does nothing (STATIC:
  // solved in Create).
  // Afterwards the mesh's current positions are rest plus displacement. O(vertices + edges).
  void Step();

  // Moves the blade (see cut::CrackCutter): the mesh is cut where the blade has passed, the
  // elastic model follows incrementally, and the vertices the cut made take displacement and
  // velocity interpolated from the vertices they came from. With SYMPLECTIC_EULER and an
  // automatic time step the step is re-estimated after a cut (small new tets lower the
  // critical step); IMPLICIT_EULER and SYMPLECTIC_EULER_SUBSTEPPED keep their step (the latter
  // counts its sub-steps again).
  // INVALID_ARGUMENT for a bad pose, which changes nothing.
  absl::Status ApplyBladePose(const cut::BladePose& pose);
  // The blade is withdrawn: everything it cut is opened.
  absl::Status WithdrawBlade();
  // Starts again from displacement `u` (by vertex index, one per vertex slot) at rest: a guess
  // near the answer, for runs that settle. Prescribed components keep their values.
  // INVALID_ARGUMENT for the wrong count or a value that is not finite.
  absl::Status SetDisplacement(std::vector<Eigen::Vector3d> u);

  const Scene& scene() const { return scene_; }
  const mesh::TetMesh& mesh() const { return scene_.mesh; }
  const fem::TensorMassModel& model() const { return *model_; }
  const fem::DynamicState& state() const { return state_; }
  double time_step() const { return time_step_; }
  // The cutter, once a blade pose was applied (null before).
  const cut::CrackCutter* cutter() const { return cutter_.get(); }
  // How the last step's linear solve went (IMPLICIT_EULER; null otherwise).
  const fem::ImplicitSolveReport* last_implicit_solve() const {
    return implicit_ != nullptr ? &implicit_->last_solve() : nullptr;
  }
  // The force law the integrator steps (null for STATIC, which is linear).
  const fem::ElasticForces* elastic_forces() const {
    return integrator_ != nullptr ? &integrator_->elastic_forces() : nullptr;
  }
  // Kinetic plus elastic energy, the elastic part by the scene's law.
  double MechanicalEnergy() const {
    return fem::MechanicalEnergy(*model_, state_, elastic_forces());
  }
  // The mechanical energy plus the potential of the constant external forces (gravity and
  // loads), -sum f . u (J): with damping it can only fall, so a rise is the integration's or
  // the cut's doing, while a piece cut free and falling turns potential into kinetic energy
  // without raising it. O(vertices).
  double TotalEnergy() const;
  // The vertices that sleep (a scene with integration.sleeping), or null.
  const fem::SleepingVertices* sleeping() const {
    return integrator_ != nullptr ? integrator_->sleeping() : nullptr;
  }
  // Sub-steps of the last step (SYMPLECTIC_EULER_SUBSTEPPED; 0 otherwise).
  int last_sub_steps() const { return substepped_ != nullptr ? substepped_->last_sub_steps() : 0; }
  // 2 / omega_max of the model as built (see fem::EstimateCriticalTimeStep).
  double critical_time_step() const { return critical_time_step_; }

  // Forgets the mesh's changes before `keep` that none of the simulation's own readers (the
  // model, sleeping vertices, the cutter) will read again: a caller with readers of its own
  // passes the oldest of their marks. Without it the log grows with every pose. O(changes kept).
  // Then frees for reuse the ids of elements removed before what those readers have read, but
  // the scene's own and those the cutter names, once enough wait that the cutter's scan pays
  // (every kIdReuseBatch removals at least): without it dead slots pile up pose after pose.
  // What is freed follows only from the cut's history, so a replay reuses ids alike; readers of
  // the log that lag (a session's views) learn a removed tet's corners from the log itself.
  void DiscardChangesBefore(mesh::ChangeMark keep);
  static constexpr std::size_t kIdReuseBatch = 1024;

  // The scene's own vertices have ids below this and keep them; those at or past it were made
  // by cuts.
  std::uint32_t tissue_vertex_bound() const { return tissue_vertex_bound_; }

  // The automatic step of IMPLICIT_EULER and SYMPLECTIC_EULER_SUBSTEPPED: the haptic rate.
  static constexpr double kImplicitTimeStep = 1e-3;  // s
  // Its linear solve's tolerance (fem::ImplicitSolveOptions): a live progressive cut of
  // lattice-tension (kerf experiment live-cut) cuts the same tets at 1e-4 as at 1e-6, with
  // 9 iterations per step at the median instead of 17 (42 at most instead of 59).
  static constexpr double kImplicitTolerance = 1e-4;

 private:
  explicit Simulation(Scene scene) : scene_(std::move(scene)) {}
  bool implicit() const { return scene_.method == kerf::v1::Integration::IMPLICIT_EULER; }
  void UpdateCurrentPositions();
  absl::Status FollowCut();
  void ReuseIdsRemovedBefore(mesh::ChangeMark read);

  Scene scene_;  // owns the mesh the model points to; Simulation is not movable
  std::unique_ptr<fem::TensorMassModel> model_;
  std::unique_ptr<fem::TimeIntegrator> integrator_;  // null for STATIC
  fem::ImplicitIntegrator* implicit_ = nullptr;      // integrator_, if IMPLICIT_EULER
  fem::SubsteppedIntegrator* substepped_ = nullptr;  // if SYMPLECTIC_EULER_SUBSTEPPED
  fem::DynamicState state_;
  double time_step_ = 0;
  double critical_time_step_ = 0;
  std::unique_ptr<cut::CrackCutter> cutter_;
  std::uint32_t tissue_vertex_bound_ = 0;
  std::uint32_t tissue_tet_bound_ = 0;
  std::size_t ids_held_ = 0;  // ids left waiting by the last reuse
};

}  // namespace kerf::sim
