#include "fem/sleeping_vertices.h"

#include <gtest/gtest.h>

#include <memory>

#include "fem/cantilever_fixture.h"
#include "fem/explicit_integrator.h"
#include "fem/implicit_integrator.h"

namespace kerf::fem {
namespace {

using mesh::Index;

enum class Method { kExplicit, kImplicit };

std::unique_ptr<TimeIntegrator> Make(Method method, const TensorMassModel& model,
                                     const BoundaryConditions& bc,
                                     std::optional<SleepOptions> sleep) {
  if (method == Method::kExplicit) {
    return std::make_unique<ExplicitIntegrator>(model, bc, ElasticOptions{}, sleep);
  }
  return std::make_unique<ImplicitIntegrator>(model, bc, ImplicitSolveOptions{.tolerance = 1e-9},
                                              ElasticOptions{}, sleep);
}

// The cantilever at rest in its static deflection, damped, stepped with and without sleeping
// from the same state.
class Sleeping : public ::testing::TestWithParam<Method> {
 protected:
  Sleeping()
      : bar_(MakeCantilever()),
        model_(*TensorMassModel::Create(bar_.mesh, Accuracy(/*mass_damping=*/6))),
        start_(DynamicState::AtRest(model_, bar_.bc)) {
    start_.displacement = *SolveStaticEquilibrium(model_, bar_.bc);
    dt_ = GetParam() == Method::kExplicit ? 0.9 * EstimateCriticalTimeStep(model_) : 1e-3;
    sleeping_ = Make(GetParam(), model_, bar_.bc, SleepOptions{.quiet_time = 0.01});
    awake_ = Make(GetParam(), model_, bar_.bc, std::nullopt);
    slept_ = awake_state_ = start_;
  }

  // Steps both runs for `seconds`.
  void StepBoth(double seconds) {
    const double end = slept_.time + seconds;
    while (slept_.time < end) {
      sleeping_->Step(dt_, &slept_);
      awake_->Step(dt_, &awake_state_);
    }
  }

  const SleepingVertices& sleep() const { return *sleeping_->sleeping(); }

  void RefreshBoth() {
    sleeping_->Refresh(bar_.bc);
    awake_->Refresh(bar_.bc);
  }

  // After 3 s more, the largest difference between the two runs' displacements is under 1e-4
  // of the largest displacement (the tolerance sleeping keeps at its default thresholds), and
  // the run without sleeping moved by more than `least_change` of it from the start.
  void ExpectTheRunsToAgreeAfter3s(double least_change) {
    StepBoth(3);
    double difference = 0, change = 0;
    for (std::size_t i = 0; i < slept_.displacement.size(); ++i) {
      difference =
          std::max(difference, (slept_.displacement[i] - awake_state_.displacement[i]).norm());
      change = std::max(change, (awake_state_.displacement[i] - start_.displacement[i]).norm());
    }
    const double largest = MaxNorm(awake_state_.displacement);
    EXPECT_LT(difference, 1e-4 * largest);
    EXPECT_GT(change, least_change * largest);
  }

  Cantilever bar_;
  TensorMassModel model_;
  DynamicState start_;
  double dt_ = 0;
  std::unique_ptr<TimeIntegrator> sleeping_, awake_;
  DynamicState slept_, awake_state_;
};

TEST_P(Sleeping, ABodyAtRestInEquilibriumFallsAsleepAndStaysPut) {
  EXPECT_EQ(sleep().awake().size(), model_.active_vertices().size());
  StepBoth(0.005);
  EXPECT_EQ(sleep().awake().size(), model_.active_vertices().size());  // not quiet long enough
  StepBoth(0.01);
  EXPECT_TRUE(sleep().awake().empty());
  EXPECT_TRUE(sleep().border().empty());
  StepBoth(0.1);
  const double deflection = MaxNorm(start_.displacement);
  for (std::size_t i = 0; i < start_.displacement.size(); ++i) {
    EXPECT_LE((slept_.displacement[i] - start_.displacement[i]).norm(), 1e-9 * deflection) << i;
    EXPECT_EQ(slept_.velocity[i], Eigen::Vector3d::Zero()) << i;
  }
}

TEST_P(Sleeping, ALoadWakesTheBodyOutwardsAndTheRunMatchesOneWithoutSleeping) {
  StepBoth(0.02);
  ASSERT_TRUE(sleep().awake().empty());
  // A load at a corner of the free end: only that vertex wakes, then its neighbours as the
  // bar bends, and so on to the clamp.
  mesh::VertexId tip{};
  for (const mesh::VertexId v : bar_.mesh.vertices()) {
    if (bar_.mesh.rest_position(v) == Eigen::Vector3d(5, 1, 1)) tip = v;
  }
  bar_.bc.loads.push_back({tip, Eigen::Vector3d(0, 0, -0.2)});
  RefreshBoth();
  ASSERT_EQ(sleep().awake().size(), 1u);
  EXPECT_EQ(sleep().awake()[0], Index(tip));
  EXPECT_FALSE(sleep().border().empty());
  StepBoth(dt_ / 2);
  const std::size_t after_one_step = sleep().awake().size();
  EXPECT_GT(after_one_step, 1u);
  EXPECT_LT(after_one_step, model_.active_vertices().size() / 2);
  ExpectTheRunsToAgreeAfter3s(/*least_change=*/1e-2);
}

// A tet at the free end split around its centre, as a cut splits tets, and a piece taken
// away: the vertices of the tets taken away and added wake, no other, and the runs agree.
TEST_P(Sleeping, ACutWakesTheVerticesOfTheTetsItChanges) {
  StepBoth(0.02);
  ASSERT_TRUE(sleep().awake().empty());
  // The tet at the free end with the largest centroid x.
  mesh::TetId t{};
  double farthest = 0;
  for (const mesh::TetId candidate : bar_.mesh.tets()) {
    double x = 0;
    for (const mesh::VertexId corner : bar_.mesh.tet(candidate)) {
      x += bar_.mesh.rest_position(corner).x();
    }
    if (x > farthest) farthest = x, t = candidate;
  }
  const mesh::TetVertices v = bar_.mesh.tet(t);
  const mesh::VertexId centre =
      bar_.mesh.AddVertex(0.25 * (bar_.mesh.rest_position(v[0]) + bar_.mesh.rest_position(v[1]) +
                                  bar_.mesh.rest_position(v[2]) + bar_.mesh.rest_position(v[3])));
  ASSERT_TRUE(bar_.mesh.RemoveTet(t).ok());
  std::vector<mesh::TetId> pieces;
  for (const auto& face : mesh::kTetFaces) {
    pieces.push_back(*bar_.mesh.AddTet({v[face[0]], v[face[1]], v[face[2]], centre}));
  }
  ASSERT_TRUE(bar_.mesh.RemoveTet(pieces[0]).ok());  // material taken away: the end sags less
  ASSERT_TRUE(model_.SyncWithMesh().ok());
  for (DynamicState* state : {&slept_, &awake_state_, &start_}) {
    state->displacement.resize(model_.vertex_count(), Eigen::Vector3d::Zero());
    state->velocity.resize(model_.vertex_count(), Eigen::Vector3d::Zero());
    Eigen::Vector3d u = Eigen::Vector3d::Zero();
    for (const mesh::VertexId corner : v) u += 0.25 * state->displacement[Index(corner)];
    state->displacement[Index(centre)] = u;
  }
  RefreshBoth();
  if (GetParam() == Method::kExplicit) dt_ = 0.9 * EstimateCriticalTimeStep(model_);
  std::vector<std::uint32_t> expected;
  for (const mesh::VertexId corner : v) {
    if (model_.mass(corner) > 0) expected.push_back(Index(corner));
  }
  expected.push_back(Index(centre));
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(std::vector<std::uint32_t>(sleep().awake().begin(), sleep().awake().end()), expected);
  ExpectTheRunsToAgreeAfter3s(/*least_change=*/5e-4);
}

TEST_P(Sleeping, AChangedPrescribedValueWakesItsVertexAndSettingTheStateWakesAll) {
  StepBoth(0.02);
  ASSERT_TRUE(sleep().awake().empty());
  PrescribedDisplacement& held = bar_.bc.prescribed.front();
  held.value = 1e-3;
  sleeping_->Refresh(bar_.bc);
  ASSERT_EQ(sleep().awake().size(), 1u);
  EXPECT_EQ(sleep().awake()[0], Index(held.vertex));
  sleeping_->WakeAll();
  EXPECT_EQ(sleep().awake().size(), model_.active_vertices().size());
}

INSTANTIATE_TEST_SUITE_P(BothIntegrators, Sleeping,
                         ::testing::Values(Method::kExplicit, Method::kImplicit),
                         [](const ::testing::TestParamInfo<Method>& param) {
                           return param.param == Method::kExplicit ? "Explicit" : "Implicit";
                         });

}  // namespace
}  // namespace kerf::fem
