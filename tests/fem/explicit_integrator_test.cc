#include "fem/explicit_integrator.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "fem/cantilever_fixture.h"
#include "fem/static_solver.h"

namespace kerf::fem {
namespace {

TEST(ExplicitIntegrator, DampedRunSettlesToTheStaticSolution) {
  const Cantilever c = MakeCantilever();
  const TensorMassModel model = *TensorMassModel::Create(c.mesh, Accuracy(/*mass_damping=*/8));
  const std::vector<Eigen::Vector3d> expected = *SolveStaticEquilibrium(model, c.bc);
  const double dt = 0.5 * EstimateCriticalTimeStep(model);
  ExplicitIntegrator integrator(model, c.bc);
  DynamicState state = DynamicState::AtRest(model, c.bc);
  for (int step = 0; step < 40000; ++step) integrator.Step(dt, &state);
  double error = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    error = std::max(error, (state.displacement[i] - expected[i]).norm());
  }
  EXPECT_LT(error, 1e-4 * MaxNorm(expected)) << "simulated " << state.time << " s";
}

// Undamped, starting from the static deflection with gravity removed: the bar vibrates.
// Returns the largest energy over the run divided by the starting energy.
double EnergyGrowth(double time_step_factor, int steps) {
  Cantilever c = MakeCantilever();
  const TensorMassModel model = *TensorMassModel::Create(c.mesh, Accuracy(0));
  DynamicState state = ReleasedFromItsDeflection(model, &c.bc);
  ExplicitIntegrator integrator(model, c.bc);
  const double dt = time_step_factor * EstimateCriticalTimeStep(model);
  const double start = MechanicalEnergy(model, state);
  double largest = start;
  for (int step = 0; step < steps; ++step) {
    integrator.Step(dt, &state);
    if (step % 100 == 0) {
      largest = std::max(largest, MechanicalEnergy(model, state));
      if (!std::isfinite(largest) || largest > 1e6 * start) break;
    }
  }
  return largest / start;
}

TEST(ExplicitIntegrator, UndampedEnergyStaysBoundedAtNineTenthsOfTheCriticalStep) {
  // Symplectic Euler keeps a modified energy exactly; the true energy oscillates within a
  // band of order (dt omega)^2 around it.
  const double growth = EnergyGrowth(0.9, 10000);
  std::printf("undamped, 0.9 x critical step, 10^4 steps: largest energy / start = %.4f\n", growth);
  EXPECT_LT(growth, 1.5);
}

TEST(ExplicitIntegrator, DivergesAtTwiceTheCriticalStep) {
  const double growth = EnergyGrowth(2.0, 10000);
  std::printf("undamped, 2 x critical step: energy grew %.3g times before the run stopped\n",
              growth);
  EXPECT_GT(growth, 1e6);
}

TEST(EstimateCriticalTimeStep, MatchesTheStabilityLimit) {
  // Just under the estimate is stable, just over it is not: the estimate is within 2%.
  const double below = EnergyGrowth(0.98, 20000), above = EnergyGrowth(1.02, 20000);
  std::printf("undamped, 2 x 10^4 steps: 0.98 x critical %.4f, 1.02 x critical %.3g\n", below,
              above);
  EXPECT_LT(below, 5.0);
  EXPECT_GT(above, 1e6);
}

}  // namespace
}  // namespace kerf::fem
