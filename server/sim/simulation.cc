#include "sim/simulation.h"

#include "fem/static_solver.h"

namespace kerf::sim {

absl::StatusOr<std::unique_ptr<Simulation>> Simulation::Create(Scene scene) {
  std::unique_ptr<Simulation> sim(new Simulation(std::move(scene)));
  absl::StatusOr<fem::TensorMassModel> model =
      fem::TensorMassModel::Create(sim->scene_.mesh, sim->scene_.material);
  if (!model.ok()) return model.status();
  sim->model_ = std::make_unique<fem::TensorMassModel>(*std::move(model));
  if (absl::Status s = fem::ValidateBoundaryConditions(sim->scene_.mesh, sim->scene_.conditions);
      !s.ok()) {
    return s;
  }
  sim->critical_time_step_ = fem::EstimateCriticalTimeStep(*sim->model_);
  sim->time_step_ =
      sim->scene_.time_step > 0 ? sim->scene_.time_step : 0.9 * sim->critical_time_step_;
  sim->state_ = fem::DynamicState::AtRest(*sim->model_, sim->scene_.conditions);
  if (sim->scene_.method == kerf::v1::Integration::STATIC) {
    absl::StatusOr<std::vector<Eigen::Vector3d>> u =
        fem::SolveStaticEquilibrium(*sim->model_, sim->scene_.conditions);
    if (!u.ok()) return u.status();
    sim->state_.displacement = *std::move(u);
  } else {
    sim->integrator_ =
        std::make_unique<fem::ExplicitIntegrator>(*sim->model_, sim->scene_.conditions);
  }
  sim->UpdateCurrentPositions();
  return sim;
}

void Simulation::Step() {
  if (integrator_ == nullptr) return;
  integrator_->Step(time_step_, &state_);
  UpdateCurrentPositions();
}

void Simulation::UpdateCurrentPositions() {
  std::span<Eigen::Vector3d> current = scene_.mesh.mutable_current_positions();
  const std::span<const Eigen::Vector3d> rest = scene_.mesh.rest_positions();
  for (std::size_t i = 0; i < current.size(); ++i) current[i] = rest[i] + state_.displacement[i];
}

}  // namespace kerf::sim
