// The cost of cutting: a pose with the blade inside a cut, on lattices of about 10k and 1M
// tets (the goal: at most 1.5 times as much on the larger one), a progressive pose by the
// number of tets the blade is in, and the final split per cut tet.
#include <benchmark/benchmark.h>

#include <array>
#include <memory>
#include <vector>

#include "absl/strings/str_cat.h"
#include "cut/crack_cutter.h"
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

// Evicts the caches by writing and reading a buffer larger than the last-level cache.
void EvictCaches() {
  static std::vector<std::uint64_t> buffer(std::size_t{64} << 20 >> 3);
  std::uint64_t sum = 0;
  for (std::uint64_t& word : buffer) sum += ++word;
  benchmark::DoNotOptimize(sum);
}

// One iteration is one pose: the blade, 13 mm deep into the top, advances 2 mm along x
// through the middle of the lattice. Every 40 poses the mesh is made afresh (not timed). With
// `evict` the caches are then evicted, so that each cut starts cold on both sizes (as after a
// physics step over a mesh larger than the cache); without, the small mesh is still in the
// cache from being built and the large one is not.
void PoseInsideACut(benchmark::State& state, CutMode mode, bool evict) {
  std::unique_ptr<mesh::TetMesh> m;
  std::unique_ptr<CrackCutter> cutter;
  double size = 0;
  int pose = 0;
  BladeLimits limits;
  limits.max_speed = 1e9;
  auto restart = [&] {
    m = LatticeWithAbout(state.range(0));
    Eigen::Vector3d high = Eigen::Vector3d::Zero();
    for (const mesh::VertexId v : m->vertices()) high = high.cwiseMax(m->rest_position(v));
    size = high.x();
    cutter =
        std::make_unique<CrackCutter>(*CrackCutter::Create(m.get(), 0.01, limits, {.mode = mode}));
    pose = 0;
    if (evict) EvictCaches();
  };
  auto apply = [&] {
    const double x = 0.5 * size - 0.04 + 0.002 * pose;
    const Eigen::Vector3d tip(x, 0.5 * size + 0.0013, size - 0.0133);
    if (!cutter->ApplyPose({0.01 * pose, tip, tip + Eigen::Vector3d(0, 0, 0.03)}).ok()) {
      state.SkipWithError("a pose was refused");
    }
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

// Deferred (second argument 0) or progressive (1); the third argument 1 evicts the caches.
void BM_PoseInsideACut(benchmark::State& state) {
  PoseInsideACut(state, state.range(1) == 1 ? CutMode::kProgressive : CutMode::kDeferred,
                 state.range(2) == 1);
}

// Time per cut tet of the final split of a whole cross-section: a blade through the full
// depth sweeps the lattice, every tet it cut waiting for it, until the timed pose takes it out
// of the far side and they are all split at once. The least snapping: the blade runs 0.37 mm
// beside a plane of vertices, which snapping would cut along without splitting a tet.
void BM_FinalSubdivision(benchmark::State& state) {
  std::size_t cut = 0;
  std::unique_ptr<mesh::TetMesh> m;
  std::unique_ptr<CrackCutter> cutter;
  for (auto _ : state) {
    state.PauseTiming();
    cutter.reset();  // made and freed outside the timed part
    m = LatticeWithAbout(state.range(0));
    double size = 0;
    for (const mesh::VertexId v : m->vertices()) size = std::max(size, m->rest_position(v).x());
    BladeLimits limits;
    limits.max_length = 3 * size;
    limits.max_step = 3 * size;
    limits.max_speed = 1e9;
    cutter = std::make_unique<CrackCutter>(*CrackCutter::Create(
        m.get(), 0.01, limits, {.mode = CutMode::kDeferred, .snap_fraction = 0}));
    const double x = 0.5 * size + 0.0037;
    const auto blade_at = [&](int k, double y) {
      const Eigen::Vector3d tip(x, y, -0.005);
      return BladePose{0.01 * k, tip, tip + Eigen::Vector3d(0, 0, size + 0.01)};
    };
    int k = 0;
    bool applied = true;
    for (; - 0.005 + 0.002 * k < size - 0.0015; ++k) {
      applied = applied && cutter->ApplyPose(blade_at(k, -0.005 + 0.002 * k)).ok();
    }
    if (!applied) {
      state.SkipWithError("a pose was refused");
      break;
    }
    if (cutter->statistics().cut_tets != 0 || cutter->waiting_tets() == 0) {
      state.SkipWithError("every tet the blade cut should still be waiting");
      break;
    }
    const BladePose out = blade_at(k, size + 0.005);
    state.ResumeTiming();
    const absl::Status last = cutter->ApplyPose(out);
    state.PauseTiming();
    if (!last.ok()) {
      state.SkipWithError("the last pose was refused");
      break;
    }
    cut = cutter->statistics().cut_tets;
    if (cutter->waiting_tets() != 0) state.SkipWithError("some cut tets were not split");
    state.ResumeTiming();
  }
  state.counters["cut_tets"] = static_cast<double>(cut);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(cut));
}

// Progressive cutting: one pose with the blade inside k tets (the argument, 1..20). A blade
// reaching down into a 2 x 2 x 8 stack of 1 cm cubes, deep enough to be in k tets (three per
// cube layer along its path; the depths were found by trying), trembles by 0.1 mm after cutting
// into it, so every pose moves or rebuilds the temporary splits of the k tets (the counter k,
// measured). The mesh is the same for every k, so the cost grows with k only.
void BM_ProgressivePoseInsideKTets(benchmark::State& state) {
  const int wanted = static_cast<int>(state.range(0));
  mesh::TetMesh m =
      *mesh::MakeBoxLattice({.cells_x = 2, .cells_y = 2, .cells_z = 8, .size = {0.02, 0.02, 0.08}});
  BladeLimits limits;
  limits.max_length = 1;
  limits.max_speed = 1e9;
  CrackCutter cutter = *CrackCutter::Create(&m, 0.01, limits);
  // Three tets a layer: the first, second and third are reached 2, 4.5 and 7.5 mm into it.
  const double depth =
      0.01 * ((wanted - 1) / 3) + 0.001 * std::array{2.0, 4.5, 7.5}[(wanted - 1) % 3];
  const auto blade_at = [&](int k, double y) {
    const Eigen::Vector3d tip(0.0063, y, 0.08 - depth);
    return BladePose{0.01 * k, tip, tip + (depth + 0.01) * Eigen::Vector3d(0.0011 / 0.09, 0, 1)};
  };
  int k = 0;
  bool applied = true;
  for (double y = -0.005; y < 0.0047; y += 0.001) {
    applied = applied && cutter.ApplyPose(blade_at(k++, y)).ok();
  }
  std::size_t inside = 0;
  const std::size_t rebuilt_before = cutter.statistics().rebuilt;
  const std::size_t moved_before = cutter.statistics().moved;
  for (auto _ : state) {
    applied = applied && cutter.ApplyPose(blade_at(k, 0.0047 + 0.0001 * (k % 2))).ok();
    ++k;
    // What a session does after every pose: the physics takes the vertices made or moved, and
    // the mesh forgets the changes every reader has seen.
    benchmark::DoNotOptimize(cutter.TakeMadeVertices());
    m.DiscardChangesBefore(cutter.synced());
    inside = 0;
    for (const std::size_t n : cutter.last_pose().tets_by_case) inside += n;
  }
  if (!applied) {
    state.SkipWithError("a pose was refused");
  } else if (static_cast<int>(inside) != wanted) {
    state.SkipWithError(absl::StrCat("the blade is in ", inside, " tets, not ", wanted).c_str());
  }
  state.counters["k"] = static_cast<double>(inside);
  state.counters["temporary_tets"] = static_cast<double>(cutter.last_pose().temporary_tets);
  // Units whose pieces were laid out again, per pose (the rest stood, only their points moving).
  state.counters["rebuilt"] =
      benchmark::Counter(static_cast<double>(cutter.statistics().rebuilt - rebuilt_before),
                         benchmark::Counter::kAvgIterations);
  // Temporary points moved with the blade, per pose.
  state.counters["moved"] =
      benchmark::Counter(static_cast<double>(cutter.statistics().moved - moved_before),
                         benchmark::Counter::kAvgIterations);
}

// Making a cutter for a mesh (its grid of tets and the tissue's surface): a session does it at
// the blade's first pose, inside a physics tick.
void BM_MakeCutter(benchmark::State& state) {
  const std::unique_ptr<mesh::TetMesh> m = LatticeWithAbout(state.range(0));
  for (auto _ : state) {
    absl::StatusOr<CrackCutter> cutter = CrackCutter::Create(m.get(), 0.01);
    if (!cutter.ok()) state.SkipWithError("the cutter was not made");
    benchmark::DoNotOptimize(cutter);
  }
  state.counters["tets"] = static_cast<double>(m->tet_count());
}

BENCHMARK(BM_MakeCutter)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PoseInsideACut)
    ->ArgsProduct({{10000, 1000000}, {0, 1}, {0, 1}})
    ->ArgNames({"tets", "progressive", "cold"})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ProgressivePoseInsideKTets)->DenseRange(1, 20)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FinalSubdivision)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(10);

}  // namespace
}  // namespace kerf::cut

BENCHMARK_MAIN();
