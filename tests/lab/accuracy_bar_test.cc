#include "lab/accuracy_bar.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fem/static_solver.h"
#include "fem/tensor_mass_model.h"
#include "support/find_vertex.h"
#include "support/status_message.h"

namespace kerf::lab {
namespace {

using kerf::testing::StatusMessage;
using Method = kerf::v1::Integration::Method;

TEST(AccuracyBar, RefusesResolutionsWithoutTheProbePoints) {
  for (const int n : {0, 3, 66}) {
    EXPECT_EQ(StatusMessage(MakeBarScene(BarLoad::kTwist, n, kerf::v1::Integration::IMPLICIT_EULER,
                                         fem::ElasticLaw::kLinear, 0)),
              absl::StrCat("the bar's resolution must be even and in [2, 64], got ", n));
  }
}

TEST(AccuracyBar, HoldsTheClampedAndLoadedFaces) {
  EXPECT_EQ(HeldDisplacement(BarLoad::kCantilever, {0, 0.3, 1}), Eigen::Vector3d::Zero());
  EXPECT_FALSE(HeldDisplacement(BarLoad::kCantilever, {5, 0.5, 0.5}).has_value());
  EXPECT_FALSE(HeldDisplacement(BarLoad::kTension, {2.5, 0, 0}).has_value());
  EXPECT_EQ(HeldDisplacement(BarLoad::kTension, {5, 1, 0}), Eigen::Vector3d(0.5, 0, 0));
  // A quarter turn about the axis y = z = 0.5 takes the corner (5, 1, 1) to (5, 0, 1).
  EXPECT_TRUE(HeldDisplacement(BarLoad::kTwist, {5, 1, 1})->isApprox(Eigen::Vector3d(0, -1, 0)));
  absl::StatusOr<sim::Scene> scene = MakeBarScene(
      BarLoad::kTwist, 2, kerf::v1::Integration::IMPLICIT_EULER, fem::ElasticLaw::kCorotational, 6);
  ASSERT_TRUE(scene.ok()) << scene.status();
  EXPECT_EQ(scene->mesh.tet_count(), 6u * 10 * 2 * 2);
  EXPECT_EQ(scene->conditions.prescribed.size(), 2u * 9 * 3);  // two faces of 3 x 3 vertices
  EXPECT_EQ(scene->material.mass_damping, 6);
  EXPECT_EQ(scene->elastic.law, fem::ElasticLaw::kCorotational);
}

// The cantilever settles to its static deflection (accuracy.md, n = 2: 0.06057) whichever
// integrator steps it.
TEST(AccuracyBar, TheCantileverSettlesToItsStaticDeflection) {
  for (const Method method :
       {kerf::v1::Integration::SYMPLECTIC_EULER, kerf::v1::Integration::SYMPLECTIC_EULER_SUBSTEPPED,
        kerf::v1::Integration::IMPLICIT_EULER}) {
    absl::StatusOr<BarSettleResult> run =
        SettleBar(BarLoad::kCantilever, 2, method, fem::ElasticLaw::kLinear, 6, 4);
    ASSERT_TRUE(run.ok()) << run.status();
    EXPECT_TRUE(run->finite);
    EXPECT_NEAR(run->quantity.z(), -0.06057, 1e-4) << kerf::v1::Integration::Method_Name(method);
    EXPECT_GE(run->simulated_seconds, 4);
    EXPECT_NEAR(run->steps * run->time_step, run->simulated_seconds, 1e-9);
  }
}

// The tension bar's quantity is the force holding its pulled face: K u summed there, u the
// static solution.
TEST(AccuracyBar, TheTensionBarsForceIsTheStaticReaction) {
  absl::StatusOr<sim::Scene> scene = MakeBarScene(
      BarLoad::kTension, 2, kerf::v1::Integration::STATIC, fem::ElasticLaw::kLinear, 0);
  ASSERT_TRUE(scene.ok()) << scene.status();
  absl::StatusOr<fem::TensorMassModel> model =
      fem::TensorMassModel::Create(scene->mesh, scene->material);
  ASSERT_TRUE(model.ok()) << model.status();
  absl::StatusOr<std::vector<Eigen::Vector3d>> u =
      fem::SolveStaticEquilibrium(*model, scene->conditions);
  ASSERT_TRUE(u.ok()) << u.status();
  std::vector<Eigen::Vector3d> f(u->size(), Eigen::Vector3d::Zero());
  model->MultiplyStiffness(*u, f);
  Eigen::Vector3d reaction = Eigen::Vector3d::Zero();
  for (const mesh::VertexId v : scene->mesh.vertices()) {
    if (scene->mesh.rest_position(v).x() == 5) reaction += f[mesh::Index(v)];
  }
  // Stiffer than the bar free to narrow (E A strain = 500), as its ends are held.
  EXPECT_GT(reaction.x(), 500);
  absl::StatusOr<BarSettleResult> run = SettleBar(
      BarLoad::kTension, 2, kerf::v1::Integration::IMPLICIT_EULER, fem::ElasticLaw::kLinear, 6, 2);
  ASSERT_TRUE(run.ok()) << run.status();
  EXPECT_LT((run->quantity - reaction).norm(), 1e-4 * reaction.norm())
      << run->quantity.transpose() << " against " << reaction.transpose();
}

// A quarter turn of one end. The linear model reads it as strain: u = (R - I) p is a turn by
// its skew part and, by its symmetric part, the end face squeezed onto the bar's axis; nearly
// incompressible (nu = 0.45), the bar bulges between the ends, its mid-length section grown
// 1.69 times. The corotational model turns the section and keeps its size (CalculiX,
// geometrically non-linear, shrinks it by 0.45%).
TEST(AccuracyBar, TheTwistShowsTheLinearModelsArtefact) {
  const Eigen::Vector3d corner(2.5, 1, 1), axis(2.5, 0.5, 0.5);
  auto section_radius = [&](const Eigen::Vector3d& p) { return (p - axis).tail<2>().norm(); };
  double growth[2];
  for (const fem::ElasticLaw law : {fem::ElasticLaw::kLinear, fem::ElasticLaw::kCorotational}) {
    absl::StatusOr<BarSettleResult> run =
        SettleBar(BarLoad::kTwist, 2, kerf::v1::Integration::IMPLICIT_EULER, law, 6, 2);
    ASSERT_TRUE(run.ok()) << run.status();
    growth[law == fem::ElasticLaw::kLinear ? 0 : 1] =
        section_radius(corner + run->quantity) / section_radius(corner);
  }
  EXPECT_GT(growth[0], 1.5);
  EXPECT_NEAR(growth[1], 1, 0.01);
}

}  // namespace
}  // namespace kerf::lab
