#include "sim/simulation.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "fem/boundary_conditions.h"
#include "fem/explicit_integrator.h"
#include "fem/implicit_integrator.h"
#include "fem/static_solver.h"
#include "fem/substepped_integrator.h"
#include "mesh/mesh_quality.h"

namespace kerf::sim {

absl::StatusOr<std::unique_ptr<Simulation>> Simulation::Create(Scene scene) {
  std::unique_ptr<Simulation> sim(new Simulation(std::move(scene)));
  sim->tissue_vertex_bound_ = sim->scene_.mesh.vertex_index_bound();
  sim->tissue_tet_bound_ = sim->scene_.mesh.tet_index_bound();
  absl::StatusOr<fem::TensorMassModel> model =
      fem::TensorMassModel::Create(sim->scene_.mesh, sim->scene_.material);
  if (!model.ok()) return model.status();
  sim->model_ = std::make_unique<fem::TensorMassModel>(*std::move(model));
  if (absl::Status s = fem::ValidateBoundaryConditions(sim->scene_.mesh, sim->scene_.conditions);
      !s.ok()) {
    return s;
  }
  sim->critical_time_step_ = fem::EstimateCriticalTimeStep(*sim->model_);
  const bool substepped = sim->scene_.method == kerf::v1::Integration::SYMPLECTIC_EULER_SUBSTEPPED;
  sim->time_step_ = sim->scene_.time_step > 0       ? sim->scene_.time_step
                    : sim->implicit() || substepped ? kImplicitTimeStep
                                                    : 0.9 * sim->critical_time_step_;
  sim->state_ = fem::DynamicState::AtRest(*sim->model_, sim->scene_.conditions);
  if (sim->scene_.method == kerf::v1::Integration::STATIC) {
    absl::StatusOr<std::vector<Eigen::Vector3d>> u =
        fem::SolveStaticEquilibrium(*sim->model_, sim->scene_.conditions);
    if (!u.ok()) return u.status();
    sim->state_.displacement = *std::move(u);
  } else if (sim->implicit()) {
    auto implicit = std::make_unique<fem::ImplicitIntegrator>(
        *sim->model_, sim->scene_.conditions,
        fem::ImplicitSolveOptions{.tolerance = kImplicitTolerance}, sim->scene_.elastic,
        sim->scene_.sleep);
    sim->implicit_ = implicit.get();
    sim->integrator_ = std::move(implicit);
  } else if (substepped) {
    auto substeps = std::make_unique<fem::SubsteppedIntegrator>(
        *sim->model_, sim->scene_.conditions, sim->scene_.elastic);
    sim->substepped_ = substeps.get();
    sim->integrator_ = std::move(substeps);
  } else {
    sim->integrator_ = std::make_unique<fem::ExplicitIntegrator>(
        *sim->model_, sim->scene_.conditions, sim->scene_.elastic, sim->scene_.sleep);
  }
  sim->UpdateCurrentPositions();
  return sim;
}

void Simulation::Step() {
  if (integrator_ == nullptr) return;
  integrator_->Step(time_step_, &state_);
  UpdateCurrentPositions();
}

absl::Status Simulation::ApplyBladePose(const cut::BladePose& pose) {
  if (cutter_ == nullptr) {
    // The spatial index's cells are about an edge long.
    absl::StatusOr<cut::CrackCutter> cutter = cut::CrackCutter::Create(
        &scene_.mesh, mesh::MeanEdgeLength(scene_.mesh), scene_.blade_limits,
        {.mode = scene_.cut_mode == kerf::v1::Cutting::DEFERRED ? cut::CutMode::kDeferred
                                                                : cut::CutMode::kProgressive,
         .snap_fraction = scene_.snap_fraction,
         .min_temporary_height = scene_.min_temporary_height});
    if (!cutter.ok()) return cutter.status();
    cutter_ = std::make_unique<cut::CrackCutter>(*std::move(cutter));
    // Slivers standing in for a tet while the blade is in it are softened.
    model_->SetStiffnessScale(
        [cutter = cutter_.get()](mesh::TetId t) { return cutter->StiffnessScale(t); });
  } else if (absl::Status s = cutter_->MeshDeformed(); !s.ok()) {
    return s;
  }
  if (absl::Status s = cutter_->ApplyPose(pose); !s.ok()) return s;
  return FollowCut();
}

absl::Status Simulation::WithdrawBlade() {
  if (cutter_ == nullptr) return absl::OkStatus();
  cutter_->Finish();
  return FollowCut();
}

absl::Status Simulation::SetDisplacement(std::vector<Eigen::Vector3d> u) {
  if (u.size() != state_.displacement.size()) {
    return absl::InvalidArgumentError(absl::StrCat("a displacement for ", u.size(),
                                                   " vertices, the mesh has ",
                                                   state_.displacement.size(), " slots"));
  }
  for (std::size_t i = 0; i < u.size(); ++i) {
    if (!u[i].allFinite()) {
      return absl::InvalidArgumentError(
          absl::StrCat("the displacement of vertex ", i, " is not finite"));
    }
  }
  for (const fem::PrescribedDisplacement& p : scene_.conditions.prescribed) {
    u[mesh::Index(p.vertex)][p.component] = p.value;
  }
  state_.displacement = std::move(u);
  std::fill(state_.velocity.begin(), state_.velocity.end(), Eigen::Vector3d::Zero());
  if (integrator_ != nullptr) integrator_->WakeAll();
  UpdateCurrentPositions();
  return absl::OkStatus();
}

void Simulation::DiscardChangesBefore(mesh::ChangeMark keep) {
  mesh::ChangeMark read = scene_.mesh.change_log().Mark();  // by all of the simulation's readers
  const auto older = [](mesh::ChangeMark mark, mesh::ChangeMark& oldest) {
    if (mark.sequence < oldest.sequence) oldest = mark;
  };
  older(model_->synced(), read);
  if (const fem::SleepingVertices* s = sleeping(); s != nullptr) older(s->seen(), read);
  if (cutter_ != nullptr) older(cutter_->synced(), read);
  ReuseIdsRemovedBefore(read);
  older(read, keep);
  scene_.mesh.DiscardChangesBefore(keep);
}

void Simulation::ReuseIdsRemovedBefore(mesh::ChangeMark read) {
  if (scene_.mesh.ids_waiting() < std::max(kIdReuseBatch, 2 * ids_held_)) return;
  const cut::CrackCutter::HeldIds held =
      cutter_ != nullptr ? cutter_->Held() : cut::CrackCutter::HeldIds{};
  scene_.mesh.ReuseIdsRemovedBefore(
      read,
      [&](mesh::VertexId v) {
        return mesh::Index(v) < tissue_vertex_bound_ || held.vertices.contains(v);
      },
      [&](mesh::TetId t) { return mesh::Index(t) < tissue_tet_bound_ || held.tets.contains(t); });
  ids_held_ = scene_.mesh.ids_waiting();
}

absl::Status Simulation::FollowCut() {
  const std::vector<cut::MadeVertex> made = cutter_->TakeMadeVertices();
  // Slots of vertices the cutter made and removed again (temporary points) count too: the
  // model and the state cover every slot of the mesh.
  const std::size_t n = scene_.mesh.vertex_index_bound();
  if (made.empty() && state_.displacement.size() == n && model_->InSyncWithMesh()) {
    return absl::OkStatus();
  }
  if (absl::Status s = model_->SyncWithMesh(); !s.ok()) return s;
  state_.displacement.resize(n, Eigen::Vector3d::Zero());
  state_.velocity.resize(n, Eigen::Vector3d::Zero());
  for (const cut::MadeVertex& m : made) {
    Eigen::Vector3d u = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) {
      u += m.weights[k] * state_.displacement[mesh::Index(m.from[k])];
      v += m.weights[k] * state_.velocity[mesh::Index(m.from[k])];
    }
    state_.displacement[mesh::Index(m.vertex)] = u;
    state_.velocity[mesh::Index(m.vertex)] = v;
  }
  if (integrator_ != nullptr) integrator_->Refresh(scene_.conditions);
  if (scene_.time_step == 0 && scene_.method == kerf::v1::Integration::SYMPLECTIC_EULER) {
    critical_time_step_ = fem::EstimateCriticalTimeStep(*model_);
    time_step_ = 0.9 * critical_time_step_;
  }
  return absl::OkStatus();
}

void Simulation::UpdateCurrentPositions() {
  std::span<Eigen::Vector3d> current = scene_.mesh.mutable_current_positions();
  const std::span<const Eigen::Vector3d> rest = scene_.mesh.rest_positions();
  for (std::size_t i = 0; i < current.size(); ++i) current[i] = rest[i] + state_.displacement[i];
}

double Simulation::TotalEnergy() const {
  const std::vector<Eigen::Vector3d> forces =
      fem::ExternalForces(scene_.conditions, model_->masses());
  double potential = 0;
  for (std::size_t i = 0; i < forces.size() && i < state_.displacement.size(); ++i) {
    potential -= forces[i].dot(state_.displacement[i]);
  }
  return MechanicalEnergy() + potential;
}

}  // namespace kerf::sim
