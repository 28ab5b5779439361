// The cost of cutting: a pose with the blade inside a cut, on lattices of about 10k and 1M
// tets (the goal: at most 1.5 times as much on the larger one), and the final subdivision per
// cut tet.
#include <benchmark/benchmark.h>

#include <memory>

#include "cut/cutter.h"
#include "mesh/box_lattice.h"

namespace kerf::cut {
namespace {

// A lattice of n^3 cubes of 1 cm with about `tets` tets.
std::unique_ptr<mesh::TetMesh> LatticeWithAbout(std::int64_t tets) {
  int n = 1;
  while (6 * (n + 1) * (n + 1) * (n + 1) <= tets) ++n;
  mesh::BoxLatticeSpec spec;
  spec.cells_x = spec.cells_y = spec.cells_z = n;
  spec.size = Eigen::Vector3d::Constant(0.01 * n);
  return std::make_unique<mesh::TetMesh>(*mesh::MakeBoxLattice(spec));
}

// One iteration is one pose: the blade, 13 mm deep into the top, advances 2 mm along x
// through the middle of the lattice. Every 40 poses the mesh is made afresh (not timed).
void BM_PoseInsideACut(benchmark::State& state) {
  std::unique_ptr<mesh::TetMesh> m;
  std::unique_ptr<Cutter> cutter;
  double size = 0;
  int pose = 0;
  BladeLimits limits;
  limits.max_speed = 1e9;
  auto restart = [&] {
    m = LatticeWithAbout(state.range(0));
    Eigen::Vector3d high = Eigen::Vector3d::Zero();
    for (const mesh::VertexId v : m->vertices()) high = high.cwiseMax(m->rest_position(v));
    size = high.x();
    cutter = std::make_unique<Cutter>(*Cutter::Create(m.get(), 0.01, limits));
    pose = 0;
  };
  auto apply = [&] {
    const double x = 0.5 * size - 0.04 + 0.002 * pose;
    const Eigen::Vector3d tip(x, 0.5 * size + 0.0013, size - 0.0133);
    (void)cutter->ApplyPose({0.01 * pose, tip, tip + Eigen::Vector3d(0, 0, 0.03)});
    ++pose;
  };
  restart();
  apply();
  for (auto _ : state) {
    if (pose == 40) {
      state.PauseTiming();
      restart();
      apply();
      state.ResumeTiming();
    }
    apply();
  }
  state.counters["tets"] = static_cast<double>(m->tet_count());
}

// Time per cut tet of the final subdivision of a whole cross-section (all its tets, cut by a
// blade through the full depth, split at once when the blade is withdrawn).
void BM_FinalSubdivision(benchmark::State& state) {
  std::size_t cut = 0;
  for (auto _ : state) {
    state.PauseTiming();
    std::unique_ptr<mesh::TetMesh> m = LatticeWithAbout(state.range(0));
    double size = 0;
    for (const mesh::VertexId v : m->vertices()) size = std::max(size, m->rest_position(v).x());
    BladeLimits limits;
    limits.max_length = 3 * size;
    limits.max_speed = 1e9;
    Cutter cutter = *Cutter::Create(m.get(), 0.01, limits);
    const double x = 0.5 * size + 0.0037;
    for (int k = 0; 0.002 * k < size + 0.01; ++k) {
      const Eigen::Vector3d tip(x, -0.005 + 0.002 * k, -0.005);
      (void)cutter.ApplyPose({0.01 * k, tip, tip + Eigen::Vector3d(0, 0, size + 0.01)});
    }
    state.ResumeTiming();
    cutter.Finish();
    cut = cutter.statistics().cut_tets;
  }
  state.counters["cut_tets"] = static_cast<double>(cut);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(cut));
}

BENCHMARK(BM_PoseInsideACut)->Arg(10000)->Arg(1000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FinalSubdivision)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(10);

}  // namespace
}  // namespace kerf::cut

BENCHMARK_MAIN();
