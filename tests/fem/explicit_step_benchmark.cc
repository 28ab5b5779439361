// The explicit step against the baseline of an Eigen sparse matrix-vector product with the
// assembled K of the same mesh, on lattices of about 1k to 1M tets, in one run.
// Goal: a step costs no more than the product, and a 100k-tet mesh steps at 1 kHz or more.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <random>

#include "fem/explicit_integrator.h"
#include "mesh/box_lattice.h"

namespace kerf::fem {
namespace {

struct Fixture {
  mesh::TetMesh mesh;
  std::unique_ptr<TensorMassModel> model;
  BoundaryConditions bc;
};

// A lattice with about `tets` tets (6 n^3), clamped at x = 0, under gravity; shared between
// the benchmarks of one size so that each builds it once.
Fixture& FixtureWithAbout(std::int64_t tets) {
  static std::map<std::int64_t, std::unique_ptr<Fixture>> cache;
  std::unique_ptr<Fixture>& f = cache[tets];
  if (f) return *f;
  int n = 1;
  while (6 * (n + 1) * (n + 1) * (n + 1) <= tets) ++n;
  mesh::BoxLatticeSpec spec;
  spec.cells_x = spec.cells_y = spec.cells_z = n;
  spec.size = Eigen::Vector3d::Constant(0.1);
  f = std::make_unique<Fixture>();
  f->mesh = *mesh::MakeBoxLattice(spec);
  Material material;
  material.mass_damping = 5;
  material.stiffness_damping = 1e-4;
  f->model = std::make_unique<TensorMassModel>(*TensorMassModel::Create(f->mesh, material));
  std::vector<mesh::VertexId> clamped;
  for (const mesh::VertexId v : f->mesh.vertices()) {
    if (f->mesh.rest_position(v).x() == 0) clamped.push_back(v);
  }
  FixVertices(clamped, &f->bc);
  f->bc.gravity = {0, 0, -9.81};
  return *f;
}

void Report(benchmark::State& state, const Fixture& f) {
  state.counters["tets"] = static_cast<double>(f.mesh.tet_count());
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  // Tets advanced per second; 1e9 over it is the cost in ns per tet per step.
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(f.mesh.tet_count()));
}

// One full explicit step: K (u + beta v), velocities, prescribed components, positions.
// Argument 1: the elastic law (ElasticLaw: 0 linear, 1 corotational: every tet's rotation
// taken and its force computed element by element).
void BM_ExplicitStep(benchmark::State& state) {
  Fixture& f = FixtureWithAbout(state.range(0));
  ExplicitIntegrator integrator(*f.model, f.bc, {.law = static_cast<ElasticLaw>(state.range(1))});
  DynamicState s = DynamicState::AtRest(*f.model, f.bc);
  const double dt = 1e-5;
  for (auto _ : state) {
    integrator.Step(dt, &s);
    benchmark::DoNotOptimize(s.displacement.data());
  }
  Report(state, f);
}

// The node/edge tensors times a displacement field (the paper's Eq. 2 for every vertex).
void BM_TensorMultiply(benchmark::State& state) {
  Fixture& f = FixtureWithAbout(state.range(0));
  std::vector<Eigen::Vector3d> u(f.model->vertex_count(), Eigen::Vector3d(1e-3, 2e-3, -1e-3));
  std::vector<Eigen::Vector3d> out(u.size());
  for (auto _ : state) {
    f.model->MultiplyStiffness(u, out);
    benchmark::DoNotOptimize(out.data());
  }
  Report(state, f);
}

// The baseline: y = K x with K assembled as an Eigen sparse matrix (row-major, doubles).
void BM_EigenSparseMatVec(benchmark::State& state) {
  Fixture& f = FixtureWithAbout(state.range(0));
  const Eigen::SparseMatrix<double, Eigen::RowMajor> k = f.model->AssembleStiffness();
  Eigen::VectorXd x = Eigen::VectorXd::Constant(k.cols(), 1e-3), y(k.rows());
  for (auto _ : state) {
    y.noalias() = k * x;
    benchmark::DoNotOptimize(y.data());
  }
  Report(state, f);
  state.counters["nonzeros"] = static_cast<double>(k.nonZeros());
}

void Sizes(benchmark::internal::Benchmark* b) {
  for (const int tets : {1000, 10000, 100000, 1000000}) b->Arg(tets);
}

BENCHMARK(BM_ExplicitStep)
    ->ArgsProduct({{1000, 10000, 100000, 1000000},
                   {static_cast<int>(ElasticLaw::kLinear),
                    static_cast<int>(ElasticLaw::kCorotational)}})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TensorMultiply)->Apply(Sizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_EigenSparseMatVec)->Apply(Sizes)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace kerf::fem

BENCHMARK_MAIN();
