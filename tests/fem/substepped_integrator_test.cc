#include "fem/substepped_integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fem/cantilever_fixture.h"
#include "mesh/box_lattice.h"

namespace kerf::fem {
namespace {

TEST(BoundCriticalTimeStep, IsUnderTheEstimateAndNotFarUnder) {
  const Cantilever c = MakeCantilever();
  const TensorMassModel model = *TensorMassModel::Create(c.mesh, Accuracy(0));
  const double bound = BoundCriticalTimeStep(model), estimate = EstimateCriticalTimeStep(model);
  std::printf("cantilever n=2: bound %.4g s, power-iteration estimate %.4g s (ratio %.3f)\n", bound,
              estimate, bound / estimate);
  EXPECT_LE(bound, estimate * (1 + 1e-3));  // the estimate is good to about 1e-3
  EXPECT_GT(bound, 0.3 * estimate);
}

// At ten times the critical step plain symplectic Euler diverges; in sub-steps the same step
// keeps the undamped energy bounded, and the sub-steps are as few as the bound allows.
TEST(SubsteppedIntegrator, StaysStableWhereOneStepWouldDiverge) {
  Cantilever c = MakeCantilever();
  const TensorMassModel model = *TensorMassModel::Create(c.mesh, Accuracy(0));
  const double dt = 10 * EstimateCriticalTimeStep(model);
  auto energy_growth = [&](TimeIntegrator& integrator, BoundaryConditions bc) {
    DynamicState state = ReleasedFromItsDeflection(model, &bc);
    integrator.Refresh(bc);
    const double start = MechanicalEnergy(model, state);
    double largest = start;
    for (int step = 0; step < 1000 && std::isfinite(largest) && largest < 1e6 * start; ++step) {
      integrator.Step(dt, &state);
      largest = std::max(largest, MechanicalEnergy(model, state));
    }
    return largest / start;
  };
  ExplicitIntegrator plain(model, c.bc);
  SubsteppedIntegrator substepped(model, c.bc);
  const double plain_growth = energy_growth(plain, c.bc);
  const double substepped_growth = energy_growth(substepped, c.bc);
  std::printf("10 x critical step, 1000 steps: plain %.3g, in %d sub-steps %.4f\n", plain_growth,
              substepped.last_sub_steps(), substepped_growth);
  EXPECT_GT(plain_growth, 1e6);
  EXPECT_LT(substepped_growth, 1.5);
  EXPECT_EQ(substepped.last_sub_steps(),
            static_cast<int>(std::ceil(
                dt / (SubsteppedIntegrator::kDefaultFraction * BoundCriticalTimeStep(model)))));
}

// After the model changes (a stiffer tet added), the next step bounds the critical step again
// and takes more sub-steps.
TEST(SubsteppedIntegrator, BoundsTheStepAgainAfterTheModelChanges) {
  mesh::BoxLatticeSpec spec;
  spec.cells_x = 2;
  spec.cells_y = spec.cells_z = 1;
  mesh::TetMesh mesh = *mesh::MakeBoxLattice(spec);
  TensorMassModel model = *TensorMassModel::Create(mesh, Accuracy(0));
  SubsteppedIntegrator integrator(model, {});
  DynamicState state = DynamicState::AtRest(model, {});
  integrator.Step(1, &state);
  const int before = integrator.last_sub_steps();
  const double bound_before = integrator.critical_time_step_bound();
  // A thin tet on one face: small, so stiff for its mass.
  const mesh::TetId t = *mesh.tets().begin();
  const mesh::TetVertices v = mesh.tet(t);
  const Eigen::Vector3d middle = (mesh.rest_position(v[0]) + mesh.rest_position(v[1]) +
                                  mesh.rest_position(v[2]) + mesh.rest_position(v[3])) /
                                 4;
  ASSERT_TRUE(mesh.RemoveTet(t).ok());
  const mesh::VertexId centre = mesh.AddVertex(middle);
  for (int skip = 0; skip < 4; ++skip) {
    mesh::TetVertices piece = v;
    piece[skip] = centre;
    ASSERT_TRUE(mesh.AddTet(piece).ok());
  }
  ASSERT_TRUE(model.SyncWithMesh().ok());
  integrator.Refresh({});
  integrator.Step(1, &state);
  EXPECT_LT(integrator.critical_time_step_bound(), bound_before);
  EXPECT_GT(integrator.last_sub_steps(), before);
}

}  // namespace
}  // namespace kerf::fem
