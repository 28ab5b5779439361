// Building a mesh with its adjacency, and local add/remove, on lattices of about 1k to 1M
// tets. The per-operation figures must not grow with mesh size.
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

// One operation = remove a random live tet and add it back (two changes, with star updates
// and change-log records), as a cut does locally.
void BM_RemoveAndAddTet(benchmark::State& state) {
  TetMesh mesh = *MakeBoxLattice(LatticeWithAbout(state.range(0)));
  std::mt19937 random(1);
  std::vector<TetId> live(mesh.tets().begin(), mesh.tets().end());
  for (auto _ : state) {
    const std::size_t i = random() % live.size();
    const TetVertices corners = mesh.tet(live[i]);
    benchmark::DoNotOptimize(mesh.RemoveTet(live[i]));
    live[i] = *mesh.AddTet(corners);
  }
  state.counters["tets"] = static_cast<double>(mesh.tet_count());
}

// One query of the tets around a random face.
void BM_TetsAroundFace(benchmark::State& state) {
  const TetMesh mesh = *MakeBoxLattice(LatticeWithAbout(state.range(0)));
  std::mt19937 random(1);
  const std::uint32_t bound = mesh.tet_index_bound();
  for (auto _ : state) {
    const TetVertices& v = mesh.tet(TetId{static_cast<std::uint32_t>(random() % bound)});
    benchmark::DoNotOptimize(mesh.TetsAroundFace(v[0], v[1], v[2]));
  }
  state.counters["tets"] = static_cast<double>(mesh.tet_count());
}

BENCHMARK(BM_BuildLattice)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RemoveAndAddTet)->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000);
BENCHMARK(BM_TetsAroundFace)->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000);

}  // namespace
}  // namespace kerf::mesh

BENCHMARK_MAIN();
