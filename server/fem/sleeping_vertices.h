// Vertices at rest, away from what moves, sleep: an integrator holds them where they are, with
// zero velocity, and spends nothing on them until they are disturbed. A step then costs in
// proportion to the vertices that move (and their neighbours), not to the mesh.
//
// A vertex falls asleep once its speed and its acceleration have stayed under the thresholds
// for a quiet time. It wakes when a tet at it is added, removed or reshaped (a cut), when its
// load or prescribed value changes, or, while it borders an awake vertex, when the net force on
// its free components (external minus elastic) over its mass exceeds the wake acceleration.
// So a disturbance wakes the body outwards as far as it carries, and no farther.
//
// Only for the linear law (the rows a step needs are the tensor-mass model's): a rotating law
// needs every tet's rotation each step.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "fem/boundary_conditions.h"
#include "fem/tensor_mass_model.h"
#include "fem/time_integrator.h"
#include "mesh/mesh_change_log.h"

namespace kerf::fem {

struct SleepOptions {
  double rest_speed = 1e-5;         // m/s
  double wake_acceleration = 1e-3;  // m/s^2; a vertex falls asleep under half of it
  double quiet_time = 0.05;         // s
};

class SleepingVertices {
 public:
  // Everything awake. The model must outlive this object.
  SleepingVertices(const TensorMassModel& model, SleepOptions options);

  // After the model synced or the conditions changed: wakes the vertices of tets added,
  // removed or reshaped since the last call, and those whose external force or prescribed
  // value changed; vertices new to the model start awake. O(vertices + changes).
  void Refresh(const BoundaryConditions& bc, std::span<const Eigen::Vector3d> external);

  // After a step of dt that moved the awake vertices: puts to sleep those that stayed at rest
  // for the quiet time (their velocity set to exactly zero) and wakes the border vertices the
  // net force `external - K u` now pulls on. O((awake + border) x edges per vertex).
  void Update(double dt, std::span<const Eigen::Vector3d> external, DynamicState* state);

  // Every vertex moves again (the state was set from outside).
  void WakeAll();

  // The active vertices that move, ascending.
  std::span<const std::uint32_t> awake() const { return awake_; }
  // The sleeping vertices with an awake neighbour: read by the awake vertices' rows.
  std::span<const std::uint32_t> border() const { return border_; }
  // The awake rows of K u (f elsewhere untouched; u read at the awake vertices and the border),
  // over the edges at awake vertices. O(awake edges).
  void MultiplyStiffness(std::span<const Eigen::Vector3d> u, std::span<Eigen::Vector3d> f) const {
    model_->MultiplyStiffnessOver(awake_, awake_edges_, u, f);
  }
  bool asleep(std::uint32_t i) const { return i < asleep_.size() && asleep_[i]; }
  // Whether the awake set changed in the last Refresh or Update.
  bool changed() const { return changed_; }
  // The mesh's change log as of the last Refresh or Update: none before it is read again.
  mesh::ChangeMark seen() const { return seen_; }

 private:
  void Wake(std::uint32_t i);
  // awake_ from the model's active vertices (after a refresh), or from itself less those that
  // fell asleep plus those woken; then border_ from their neighbours.
  void RebuildAwake();
  void UpdateAwake();
  // border_ and awake_edges_ from awake_.
  void RebuildBorder();

  const TensorMassModel* model_;
  SleepOptions options_;
  mesh::ChangeMark seen_;
  std::vector<bool> asleep_;                    // by vertex index
  std::vector<double> quiet_;                   // s at rest so far, by vertex index
  std::vector<Eigen::Vector3d> last_velocity_;  // at the last Update, by vertex index
  std::vector<Eigen::Vector3d> free_;           // per component: 1 if not prescribed
  std::vector<Eigen::Vector3d> external_;       // as at the last Refresh
  std::vector<PrescribedDisplacement> prescribed_;
  std::vector<std::uint32_t> awake_, border_, awake_edges_;
  std::vector<std::uint32_t> woken_;    // since the last UpdateAwake
  std::vector<bool> on_border_;         // by vertex index, scratch for RebuildBorder
  std::vector<std::uint64_t> listed_;   // a bit per edge, scratch for RebuildBorder
  std::vector<Eigen::Vector3d> force_;  // K u on the border, by vertex index
  bool changed_ = true;
};

}  // namespace kerf::fem
