#include "lab/live_cut.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "fem/explicit_integrator.h"
#include "geometry/tet_measures.h"
#include "mesh/mesh_quality.h"
#include "mesh/mesh_validation.h"
#include "sim/simulation.h"

namespace kerf::lab {
namespace {

// The path's pose at time t (s, as written), linear between poses, held after the last.
cut::BladePose PoseAt(const std::vector<cut::BladePose>& path, double t) {
  std::size_t k = 0;
  while (k + 1 < path.size() && path[k + 1].time < t) ++k;
  if (k + 1 < path.size() && t > path[k].time) return cut::InterpolatePose(path[k], path[k + 1], t);
  return path[k];
}

double SmallestHeight(const mesh::TetMesh& mesh) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const mesh::TetId t : mesh.tets()) {
    const mesh::TetVertices& v = mesh.tet(t);
    smallest = std::min(
        smallest, geometry::SmallestHeight(mesh.rest_position(v[0]), mesh.rest_position(v[1]),
                                           mesh.rest_position(v[2]), mesh.rest_position(v[3])));
  }
  return smallest;
}

double LargestSpeed(const fem::DynamicState& state) {
  double largest = 0;
  for (const Eigen::Vector3d& v : state.velocity) largest = std::max(largest, v.norm());
  return largest;
}

}  // namespace

absl::StatusOr<kerf::v1::LiveCutRow> RunLiveCut(sim::Scene scene,
                                                const std::vector<cut::BladePose>& path,
                                                const LiveCutOptions& options) {
  if (scene.method == kerf::v1::Integration::STATIC) {
    return absl::FailedPreconditionError("a live cut needs a dynamic scene, not STATIC");
  }
  if (path.empty()) return absl::InvalidArgumentError("the blade path has no pose");
  absl::StatusOr<std::unique_ptr<sim::Simulation>> created =
      sim::Simulation::Create(std::move(scene));
  if (!created.ok()) return created.status();
  sim::Simulation& sim = **created;
  double time = 0;
  std::vector<int> iterations;  // of the linear solves
  std::vector<int> sub_steps;
  auto step_to = [&](double until) {
    while (time < until) {
      sim.Step();
      time += sim.time_step();
      if (sim.last_implicit_solve() != nullptr) {
        iterations.push_back(sim.last_implicit_solve()->iterations);
      }
      if (sim.last_sub_steps() > 0) sub_steps.push_back(sim.last_sub_steps());
    }
  };
  step_to(options.settle_seconds);
  iterations.clear();  // only those from the first pose count
  sub_steps.clear();

  kerf::v1::LiveCutRow row;
  // The energy the settled body holds, and what it may gain: the rise of the total energy (the
  // work of gravity and loads counted), measured against it.
  const double start_energy = sim.MechanicalEnergy();
  const double start_total = sim.TotalEnergy();
  const double start_time = time;
  const double duration = path.back().time * options.slow_down;
  const double pose_period = 1 / options.pose_rate_hz;
  double largest_ratio = 1, largest_speed = 0;
  const auto wall_start = std::chrono::steady_clock::now();
  for (int n = 0; n * pose_period <= duration + 1e-12; ++n) {
    const double elapsed = n * pose_period;
    cut::BladePose pose = PoseAt(path, elapsed / options.slow_down);
    pose.time = start_time + elapsed;
    if (absl::Status s = sim.ApplyBladePose(pose); !s.ok()) return s;
    step_to(start_time + elapsed + pose_period);
    row.set_poses(n + 1);
    const double ratio = (start_energy + sim.TotalEnergy() - start_total) / start_energy;
    largest_speed = std::max(largest_speed, LargestSpeed(sim.state()));
    largest_ratio = std::isfinite(ratio) ? std::max(largest_ratio, ratio) : ratio;
    if (!std::isfinite(ratio) || ratio > options.blow_up_energy_ratio) {
      row.set_blew_up(true);
      row.set_blew_up_after(elapsed + pose_period);
      break;
    }
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count() >
        options.max_wall_seconds) {
      row.set_stopped_after(elapsed + pose_period);
      break;
    }
  }
  if (!row.blew_up() && row.stopped_after() == 0) {
    if (absl::Status s = sim.WithdrawBlade(); !s.ok()) return s;
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  row.set_wall_seconds_per_simulated_second(wall / (time - start_time));
  auto median_and_max = [](std::vector<int> counts) -> std::pair<int, int> {
    if (counts.empty()) return {0, 0};
    std::sort(counts.begin(), counts.end());
    return {counts[counts.size() / 2], counts.back()};
  };
  const auto [iterations_median, iterations_max] = median_and_max(std::move(iterations));
  row.set_solve_iterations_median(iterations_median);
  row.set_solve_iterations_max(iterations_max);
  const auto [sub_steps_median, sub_steps_max] = median_and_max(std::move(sub_steps));
  row.set_sub_steps_median(sub_steps_median);
  row.set_sub_steps_max(sub_steps_max);
  row.set_largest_energy_ratio(largest_ratio);
  row.set_largest_speed(largest_speed);
  row.set_smallest_height(SmallestHeight(sim.mesh()));
  row.set_critical_time_step(fem::EstimateCriticalTimeStep(sim.model()));
  row.set_time_step(sim.time_step());
  const cut::CutStatistics& stats = sim.cutter()->statistics();
  row.set_cut_tets(static_cast<std::uint32_t>(stats.cut_tets));
  row.set_tets_after(static_cast<std::uint32_t>(sim.mesh().tet_count()));
  row.set_valid(mesh::ValidateMesh(sim.mesh()).ok());
  const mesh::MeshQuality quality = mesh::MeasureMeshQuality(sim.mesh());
  row.set_smallest_radius_ratio(quality.min_radius_ratio);
  row.set_smallest_dihedral_deg(quality.min_dihedral_deg);
  return row;
}

}  // namespace kerf::lab
