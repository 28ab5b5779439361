#include "fem/implicit_integrator.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "fem/cantilever_fixture.h"
#include "fem/explicit_integrator.h"
#include "fem/static_solver.h"

namespace kerf::fem {
namespace {

double MaxError(const std::vector<Eigen::Vector3d>& u, const std::vector<Eigen::Vector3d>& v) {
  double error = 0;
  for (std::size_t i = 0; i < v.size(); ++i) error = std::max(error, (u[i] - v[i]).norm());
  return error;
}

TEST(ImplicitIntegrator, SettlesToTheStaticSolutionAtStepsFarAboveTheCriticalOne) {
  const Cantilever c = MakeCantilever();
  const TensorMassModel model = *TensorMassModel::Create(c.mesh, Accuracy(/*mass_damping=*/0));
  const std::vector<Eigen::Vector3d> expected = *SolveStaticEquilibrium(model, c.bc);
  // Undamped: only backward Euler's own dissipation settles it.
  const double dt = 100 * EstimateCriticalTimeStep(model);
  ImplicitIntegrator integrator(model, c.bc, {.tolerance = 1e-10});
  DynamicState state = DynamicState::AtRest(model, c.bc);
  for (int step = 0; step < 400; ++step) integrator.Step(dt, &state);
  EXPECT_LT(MaxError(state.displacement, expected), 1e-6 * MaxNorm(expected))
      << "simulated " << state.time << " s";
}

// Undamped, from the static deflection with gravity removed: the bar vibrates, and backward
// Euler may only take energy away, at every step and whatever the step.
TEST(ImplicitIntegrator, UndampedEnergyNeverGrowsAtAnyStep) {
  for (const double factor : {0.5, 2.0, 20.0, 200.0}) {
    Cantilever c = MakeCantilever();
    const TensorMassModel model = *TensorMassModel::Create(c.mesh, Accuracy(0));
    DynamicState state = ReleasedFromItsDeflection(model, &c.bc);
    ImplicitIntegrator integrator(model, c.bc, {.tolerance = 1e-12});
    const double dt = factor * EstimateCriticalTimeStep(model);
    const double start = MechanicalEnergy(model, state);
    double previous = start;
    for (int step = 0; step < 300; ++step) {
      integrator.Step(dt, &state);
      const double energy = MechanicalEnergy(model, state);
      ASSERT_LE(energy, previous * (1 + 1e-9)) << factor << " x critical, step " << step;
      previous = energy;
    }
    std::printf("undamped, %g x critical step, 300 steps: energy / start = %.4g\n", factor,
                previous / start);
    EXPECT_LT(previous, start);
  }
}

TEST(ImplicitIntegrator, KeepsMostEnergyOverAPeriodAtSmallSteps) {
  // Backward Euler's damping of a mode is about omega dt per step: at a tenth of the
  // critical step the bar's first modes lose little, so the method is not just a damper.
  Cantilever c = MakeCantilever();
  const TensorMassModel model = *TensorMassModel::Create(c.mesh, Accuracy(0));
  DynamicState state = ReleasedFromItsDeflection(model, &c.bc);
  ImplicitIntegrator integrator(model, c.bc, {.tolerance = 1e-12});
  const double dt = 0.1 * EstimateCriticalTimeStep(model);
  const double start = MechanicalEnergy(model, state);
  for (int step = 0; step < 200; ++step) integrator.Step(dt, &state);
  const double kept = MechanicalEnergy(model, state) / start;
  std::printf("undamped, 0.1 x critical step, 200 steps: energy / start = %.4f\n", kept);
  EXPECT_GT(kept, 0.9);
  EXPECT_LT(kept, 1.0);
}

TEST(ImplicitIntegrator, HoldsPrescribedComponentsAndSolvesToTheTolerance) {
  Cantilever c = MakeCantilever();
  // Pull the free end 1% longer, as the lattice-tension scene does.
  for (const mesh::VertexId v : c.mesh.vertices()) {
    if (c.mesh.rest_position(v).x() == 5) c.bc.prescribed.push_back({v, 0, 0.05});
  }
  const TensorMassModel model = *TensorMassModel::Create(c.mesh, Accuracy(8));
  const ImplicitSolveOptions options{.tolerance = 1e-8, .max_iterations = 500};
  ImplicitIntegrator integrator(model, c.bc, options);
  DynamicState state = DynamicState::AtRest(model, c.bc);
  for (int step = 0; step < 50; ++step) {
    integrator.Step(1e-2, &state);
    ASSERT_LE(integrator.last_solve().relative_residual, options.tolerance) << step;
    ASSERT_LT(integrator.last_solve().iterations, options.max_iterations) << step;
  }
  for (const PrescribedDisplacement& p : c.bc.prescribed) {
    EXPECT_EQ(state.displacement[mesh::Index(p.vertex)][p.component], p.value);
    EXPECT_EQ(state.velocity[mesh::Index(p.vertex)][p.component], 0);
  }
  // The free end's neighbours follow the pull.
  const std::vector<Eigen::Vector3d> expected = *SolveStaticEquilibrium(model, c.bc);
  EXPECT_GT(MaxNorm(state.displacement), 0.04);
  std::printf("50 steps of 10 ms: largest distance from equilibrium %.3g m\n",
              MaxError(state.displacement, expected));
}

// The solve starts from the velocity the last step's change predicts: a body falling freely
// (nothing held, so the tissue is not strained) gains the same velocity every step, so from
// the second step on the start is the answer to the first step's tolerance, and at most one
// iteration polishes it. Started from the current velocity instead, every step would iterate
// as much as the first.
TEST(ImplicitIntegrator, StartsFromTheVelocityTheLastChangePredicts) {
  Cantilever c = MakeCantilever();
  c.bc.prescribed.clear();
  const TensorMassModel model = *TensorMassModel::Create(c.mesh, Accuracy(0));
  ImplicitIntegrator integrator(model, c.bc);
  DynamicState state = DynamicState::AtRest(model, c.bc);
  integrator.Step(1e-2, &state);
  const int first = integrator.last_solve().iterations;
  EXPECT_GT(first, 1);
  for (int step = 1; step < 10; ++step) {
    integrator.Step(1e-2, &state);
    EXPECT_LE(integrator.last_solve().iterations, 1) << step;
  }
  // v = g t after ten steps, to the tolerance.
  for (const mesh::VertexId v : c.mesh.vertices()) {
    EXPECT_NEAR(state.velocity[mesh::Index(v)].z(), -0.1, 1e-6);
  }
}

}  // namespace
}  // namespace kerf::fem
