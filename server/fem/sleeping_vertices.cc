#include "fem/sleeping_vertices.h"

#include <algorithm>
#include <bit>

#include "base/check.h"

namespace kerf::fem {

using mesh::Index;

SleepingVertices::SleepingVertices(const TensorMassModel& model, SleepOptions options)
    : model_(&model), options_(options), seen_(model.mesh().change_log().Mark()) {
  KERF_CHECK(options.rest_speed >= 0 && options.wake_acceleration > 0 && options.quiet_time >= 0);
}

void SleepingVertices::Wake(std::uint32_t i) {
  quiet_[i] = 0;
  if (!asleep_[i]) return;
  asleep_[i] = false;
  woken_.push_back(i);
}

void SleepingVertices::Refresh(const BoundaryConditions& bc,
                               std::span<const Eigen::Vector3d> external) {
  const std::size_t n = model_->vertex_count();
  asleep_.resize(n, false);
  quiet_.resize(n, 0);
  last_velocity_.resize(n, Eigen::Vector3d::Zero());
  on_border_.resize(n, false);
  force_.resize(n, Eigen::Vector3d::Zero());
  const mesh::TetMesh& mesh = model_->mesh();
  const absl::StatusOr<mesh::MeshChanges> changes = mesh.change_log().ChangesSince(seen_);
  if (!changes.ok()) {  // the log was trimmed past what this object saw: wake everything
    for (std::uint32_t i = 0; i < n; ++i) Wake(i);
  } else {
    for (const mesh::TetId t : changes->added_tets) {
      for (const mesh::VertexId v : mesh.tet(t)) Wake(Index(v));
    }
    for (const mesh::TetVertices& corners : changes->removed_tet_corners) {
      for (const mesh::VertexId v : corners) Wake(Index(v));
    }
    for (const mesh::VertexId moved : changes->moved_vertices) {
      for (const mesh::TetId t : mesh.TetsAround(moved)) {
        for (const mesh::VertexId v : mesh.tet(t)) Wake(Index(v));
      }
    }
  }
  seen_ = mesh.change_log().Mark();

  external_.resize(n, Eigen::Vector3d::Zero());
  for (std::uint32_t i = 0; i < n; ++i) {
    if (external[i] != external_[i]) Wake(i);
    external_[i] = external[i];
  }
  // Prescriptions changed: entry by entry if the list kept its length, else all of them.
  const auto same = [](const PrescribedDisplacement& p, const PrescribedDisplacement& q) {
    return p.vertex == q.vertex && p.component == q.component && p.value == q.value;
  };
  if (bc.prescribed.size() == prescribed_.size()) {
    for (std::size_t k = 0; k < prescribed_.size(); ++k) {
      if (same(prescribed_[k], bc.prescribed[k])) continue;
      Wake(Index(prescribed_[k].vertex));
      Wake(Index(bc.prescribed[k].vertex));
    }
  } else {
    for (const PrescribedDisplacement& p : prescribed_) Wake(Index(p.vertex));
    for (const PrescribedDisplacement& p : bc.prescribed) Wake(Index(p.vertex));
  }
  prescribed_ = bc.prescribed;
  free_.assign(n, Eigen::Vector3d::Ones());
  for (const PrescribedDisplacement& p : prescribed_) free_[Index(p.vertex)][p.component] = 0;
  RebuildAwake();
}

void SleepingVertices::Update(double dt, std::span<const Eigen::Vector3d> external,
                              DynamicState* state) {
  KERF_CHECK(dt > 0);
  changed_ = false;
  const double calm = options_.wake_acceleration / 2;
  bool fell_asleep = false;
  for (const std::uint32_t i : awake_) {
    Eigen::Vector3d& v = state->velocity[i];
    const bool at_rest =
        v.norm() <= options_.rest_speed && (v - last_velocity_[i]).norm() <= calm * dt;
    quiet_[i] = at_rest ? quiet_[i] + dt : 0;
    if (quiet_[i] >= options_.quiet_time) {
      asleep_[i] = true;
      v.setZero();
      fell_asleep = true;
    }
    last_velocity_[i] = v;
  }
  if (fell_asleep) {
    std::erase_if(awake_, [&](std::uint32_t i) { return asleep_[i]; });
    changed_ = true;
    RebuildBorder();
  }
  // The border is held where it fell asleep: wake it where the awake vertices now pull.
  model_->MultiplyStiffnessRows(border_, state->displacement, force_);
  for (const std::uint32_t j : border_) {
    const Eigen::Vector3d net = (external[j] - force_[j]).cwiseProduct(free_[j]);
    if (net.norm() > options_.wake_acceleration * model_->masses()[j]) Wake(j);
  }
  if (!woken_.empty()) UpdateAwake();
}

void SleepingVertices::WakeAll() {
  for (std::uint32_t i = 0; i < asleep_.size(); ++i) Wake(i);
  RebuildAwake();
}

void SleepingVertices::RebuildAwake() {
  woken_.clear();
  awake_.clear();
  for (const std::uint32_t i : model_->active_vertices()) {
    if (!asleep_[i]) awake_.push_back(i);
  }
  changed_ = true;
  RebuildBorder();
}

void SleepingVertices::UpdateAwake() {
  for (const std::uint32_t i : woken_) {
    if (model_->masses()[i] > 0) awake_.push_back(i);
  }
  woken_.clear();
  std::sort(awake_.begin(), awake_.end());
  changed_ = true;
  RebuildBorder();
}

void SleepingVertices::RebuildBorder() {
  border_.clear();
  awake_edges_.clear();
  listed_.resize((model_->edges().size() + 63) / 64, 0);
  for (const std::uint32_t i : awake_) {
    for (const std::uint32_t slot : model_->edges_at(i)) {
      const EdgeTensor& e = model_->edges()[slot];
      const std::uint32_t j = Index(e.a) == i ? Index(e.b) : Index(e.a);
      // An edge between two awake vertices is listed from its first end only.
      if (!asleep_[j] && Index(e.a) != i) continue;
      listed_[slot / 64] |= std::uint64_t{1} << (slot % 64);
      if (asleep_[j] && !on_border_[j]) {
        on_border_[j] = true;
        border_.push_back(j);
      }
    }
  }
  // In the model's order, so that a multiply reads its edges front to back.
  for (std::size_t word = 0; word < listed_.size(); ++word) {
    for (std::uint64_t bits = listed_[word]; bits != 0; bits &= bits - 1) {
      awake_edges_.push_back(static_cast<std::uint32_t>(64 * word + std::countr_zero(bits)));
    }
    listed_[word] = 0;
  }
  for (const std::uint32_t j : border_) on_border_[j] = false;
}

}  // namespace kerf::fem
