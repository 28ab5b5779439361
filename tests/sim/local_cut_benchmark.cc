// A local cut on a large mesh, with and without sleeping vertices (README: Sleeping vertices).
// A slab of tissue (32 x 8 x 8 cm at about 100k tets; soft tissue, mass damping 20/s) lies on
// a support (its base held) and rests in its static sag under gravity; the sleeping run falls
// asleep. Then a blade cuts 2 cm deep into one end, 4 cm across, a pose and a backward-Euler
// step per millisecond, and is withdrawn (the whole crack opens), and both runs step on for
// 0.2 s. The two runs alternate pose by pose and step by step, so their ratio is measured in
// one run.
// Arguments: about how many tets, and log10 of the wake acceleration (m/s^2).
// Counters: the full run's wall time per pose while cutting and per step after, the sleeping
// run's over the full run's, the share of vertices awake when the blade is withdrawn and at
// the end, and the largest difference between the two runs' displacements at the end over
// the largest displacement (the tolerance sleeping keeps) and over the largest change the cut
// made.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>

#include "absl/strings/str_cat.h"
#include "fem/sleeping_vertices.h"
#include "fem/static_solver.h"
#include "sim/scene.h"
#include "sim/simulation.h"

namespace kerf::sim {
namespace {

using Clock = std::chrono::steady_clock;

// A slab four cells long per cell of width and height (5 mm cubes of six tets), about `tets`
// tets, held at its base, under gravity.
std::unique_ptr<Simulation> Slab(std::int64_t tets, std::optional<double> wake_acceleration) {
  int n = 1;
  while (6 * 4 * (n + 1) * (n + 1) * (n + 1) <= tets) ++n;
  const double cell = 0.005;  // m
  const std::string text = absl::StrCat(
      "mesh { lattice { cells_x: ", 4 * n, " cells_y: ", n, " cells_z: ", n,
      " size { x: ", 4 * n * cell, " y: ", n * cell, " z: ", n * cell,
      " } } }\n"
      "material { youngs_modulus: 5000 poisson_ratio: 0.45 density: 1000 mass_damping: 20 }\n"
      "displacements { vertices { half_space { point { z: 0 } normal { z: -1 } } } }\n"
      "gravity { z: -9.81 }\n"
      "integration { method: IMPLICIT_EULER",
      wake_acceleration.has_value()
          ? absl::StrCat(" sleeping { wake_acceleration: ", *wake_acceleration, " } }\n")
          : " }\n");
  return *Simulation::Create(*BuildScene(*ParseSceneText(text, "slab"), "."));
}

// The static sag of the slab of about `tets` tets, solved once per size.
const std::vector<Eigen::Vector3d>& Sag(std::int64_t tets, const Simulation& slab) {
  static std::map<std::int64_t, std::vector<Eigen::Vector3d>> cache;
  auto [it, inserted] = cache.try_emplace(tets);
  if (inserted) it->second = *fem::SolveStaticEquilibrium(slab.model(), slab.scene().conditions);
  return it->second;
}

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

double AwakeShare(const Simulation& sim) {
  return static_cast<double>(sim.sleeping()->awake().size()) /
         static_cast<double>(sim.model().active_vertices().size());
}

void BM_LocalCut(benchmark::State& state) {
  std::unique_ptr<Simulation> sleeping = Slab(state.range(0), std::pow(10.0, state.range(1))),
                              full = Slab(state.range(0), std::nullopt);
  const std::vector<Eigen::Vector3d>& sag = Sag(state.range(0), *full);
  for (Simulation* sim : {sleeping.get(), full.get()}) {
    if (!sim->SetDisplacement(sag).ok()) state.SkipWithError("the sag was refused");
  }
  // At rest for 0.1 s: the sleeping run falls asleep (quiet for 0.05 s by default).
  for (int i = 0; i < 100; ++i) {
    sleeping->Step();
    full->Step();
  }
  double top = 0;
  for (const mesh::VertexId v : full->mesh().vertices()) {
    top = std::max(top, full->mesh().rest_position(v).z());
  }
  constexpr int kPoses = 41, kStepsAfter = 200;
  double cutting[2] = {0, 0}, after[2] = {0, 0};
  for (auto _ : state) {
    for (int pose = 0; pose < kPoses; ++pose) {
      const double y = -0.005 + 0.001 * pose;
      const cut::BladePose blade{.time = 0.001 * pose,
                                 .tip = Eigen::Vector3d(0.0137, y, top - 0.02),
                                 .heel = Eigen::Vector3d(0.0137, y, top + 0.02)};
      int k = 0;
      for (Simulation* sim : {sleeping.get(), full.get()}) {
        const Clock::time_point start = Clock::now();
        if (!sim->ApplyBladePose(blade).ok()) state.SkipWithError("a pose was refused");
        sim->Step();
        cutting[k++] += Seconds(start);
      }
    }
    state.counters["awake_withdrawn"] = AwakeShare(*sleeping);
    for (int step = 0; step < kStepsAfter; ++step) {
      int k = 0;
      for (Simulation* sim : {sleeping.get(), full.get()}) {
        const Clock::time_point start = Clock::now();
        if (step == 0 && !sim->WithdrawBlade().ok()) state.SkipWithError("withdrawing failed");
        sim->Step();
        after[k++] += Seconds(start);
      }
    }
  }
  double difference = 0, largest = 0, change = 0;
  const std::vector<Eigen::Vector3d>& u = sleeping->state().displacement;
  const std::vector<Eigen::Vector3d>& w = full->state().displacement;
  for (std::size_t i = 0; i < w.size(); ++i) {
    difference = std::max(difference, (u[i] - w[i]).norm());
    largest = std::max(largest, w[i].norm());
    if (i < sag.size()) change = std::max(change, (w[i] - sag[i]).norm());
  }
  const auto runs = static_cast<double>(state.iterations());
  state.counters["tets"] = static_cast<double>(full->mesh().tet_count());
  state.counters["cut_tets"] = static_cast<double>(full->cutter()->statistics().cut_tets);
  state.counters["pose_ms_full"] = 1e3 * cutting[1] / (kPoses * runs);
  state.counters["pose_ratio"] = cutting[0] / cutting[1];
  state.counters["step_ms_full"] = 1e3 * after[1] / (kStepsAfter * runs);
  state.counters["step_ratio"] = after[0] / after[1];
  state.counters["awake_end"] = AwakeShare(*sleeping);
  state.counters["difference"] = difference / largest;
  state.counters["difference_of_change"] = difference / change;
}
// The cut changes the mesh, so the protocol runs once per configuration.
BENCHMARK(BM_LocalCut)
    ->ArgsProduct({{10000, 100000}, {-3, -2, -1}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace kerf::sim

BENCHMARK_MAIN();
