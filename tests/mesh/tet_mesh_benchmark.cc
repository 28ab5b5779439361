// Building a mesh with its adjacency, and local add/remove and face queries, on lattices of
// about 1k to 1M tets. The per-operation cost must not grow with mesh size.
//
// Two access patterns for the per-operation benchmarks:
//   Local:  operations on ~1000 tets around the mesh centre, as a blade works on the tets near
//           it. This measures the algorithm.
//   Random: operations on tets drawn from the whole mesh. On a large mesh most accesses miss
//           the cache, so this measures memory latency as much as the algorithm.
#include <benchmark/benchmark.h>

#include <random>

#include "mesh/box_lattice.h"

namespace kerf::mesh {
namespace {

// Lattice dimensions with 6 n^3 tets near the requested count.
BoxLatticeSpec LatticeWithAbout(std::int64_t tets) {
  BoxLatticeSpec spec;
  int n = 1;
  while (6 * (n + 1) * (n + 1) * (n + 1) <= tets) ++n;
  spec.cells_x = spec.cells_y = spec.cells_z = n;
  return spec;
}

enum class Pattern { kLocal, kRandom };

// The tets the operations work on: all of them, or those whose first vertex lies within a
// few cells of the lattice centre (about 1000 tets, or the whole mesh if smaller).
std::vector<TetId> WorkingSet(const TetMesh& mesh, const BoxLatticeSpec& spec, Pattern pattern) {
  std::vector<TetId> tets;
  const Eigen::Vector3d centre = 0.5 * Eigen::Vector3d(spec.cells_x, spec.cells_y, spec.cells_z);
  for (const TetId t : mesh.tets()) {
    const Eigen::Vector3d& p = mesh.rest_position(mesh.tet(t)[0]);
    if (pattern == Pattern::kRandom || (p - centre).lpNorm<Eigen::Infinity>() < 2.6) {
      tets.push_back(t);
    }
  }
  return tets;
}

// Builds the lattice: vertices, tets and every vertex star. items_per_second counts tets.
void BM_BuildLattice(benchmark::State& state) {
  const BoxLatticeSpec spec = LatticeWithAbout(state.range(0));
  std::size_t tets = 0;
  for (auto _ : state) {
    absl::StatusOr<TetMesh> mesh = MakeBoxLattice(spec);
    tets = mesh->tet_count();
    benchmark::DoNotOptimize(mesh);
  }
  state.counters["tets"] = static_cast<double>(tets);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(tets));
}

// One operation = remove a tet and add it back (two changes, with star updates and
// change-log records), as a cut replaces tets.
template <Pattern pattern>
void BM_RemoveAndAddTet(benchmark::State& state) {
  const BoxLatticeSpec spec = LatticeWithAbout(state.range(0));
  TetMesh mesh = *MakeBoxLattice(spec);
  std::vector<TetId> working = WorkingSet(mesh, spec, pattern);
  std::mt19937 random(1);
  for (auto _ : state) {
    const std::size_t i = random() % working.size();
    const TetVertices corners = mesh.tet(working[i]);
    benchmark::DoNotOptimize(mesh.RemoveTet(working[i]));
    working[i] = *mesh.AddTet(corners);
  }
  state.counters["tets"] = static_cast<double>(mesh.tet_count());
  state.counters["working_set"] = static_cast<double>(working.size());
}

// One query of the tets around a face of a tet in the working set.
template <Pattern pattern>
void BM_TetsAroundFace(benchmark::State& state) {
  const BoxLatticeSpec spec = LatticeWithAbout(state.range(0));
  const TetMesh mesh = *MakeBoxLattice(spec);
  const std::vector<TetId> working = WorkingSet(mesh, spec, pattern);
  std::mt19937 random(1);
  for (auto _ : state) {
    const TetVertices& v = mesh.tet(working[random() % working.size()]);
    benchmark::DoNotOptimize(mesh.TetsAroundFace(v[0], v[1], v[2]));
  }
  state.counters["tets"] = static_cast<double>(mesh.tet_count());
  state.counters["working_set"] = static_cast<double>(working.size());
}

void Sizes(benchmark::internal::Benchmark* b) {
  for (const int tets : {1000, 10000, 100000, 1000000}) b->Arg(tets);
}

BENCHMARK(BM_BuildLattice)->Apply(Sizes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RemoveAndAddTet<Pattern::kLocal>)->Apply(Sizes);
BENCHMARK(BM_RemoveAndAddTet<Pattern::kRandom>)->Apply(Sizes);
BENCHMARK(BM_TetsAroundFace<Pattern::kLocal>)->Apply(Sizes);
BENCHMARK(BM_TetsAroundFace<Pattern::kRandom>)->Apply(Sizes);

}  // namespace
}  // namespace kerf::mesh

BENCHMARK_MAIN();
