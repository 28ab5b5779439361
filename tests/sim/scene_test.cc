#include "sim/scene.h"

#include <gtest/gtest.h>

#include "absl/strings/str_replace.h"
#include "fem/static_solver.h"
#include "sim/simulation.h"
#include "support/find_vertex.h"
#include "support/status_message.h"

namespace kerf::sim {
namespace {

using kerf::testing::StatusMessage;

TEST(LoadScene, EmbeddedScenesBuild) {
  EXPECT_EQ(
      EmbeddedSceneNames(),
      (std::vector<std::string>{"lattice-tension", "lattice-tension-deferred", "bar-cantilever"}));
  absl::StatusOr<Scene> tension = LoadScene("lattice-tension");
  ASSERT_TRUE(tension.ok()) << tension.status();
  EXPECT_EQ(tension->mesh.tet_count(), 576u);
  // 5 x 5 vertices at each end of the 4 x 6 x 4 lattice, three components each.
  EXPECT_EQ(tension->conditions.prescribed.size(), 2u * 25 * 3);
  double pulled = 0;
  for (const auto& p : tension->conditions.prescribed) pulled = std::max(pulled, p.value);
  EXPECT_DOUBLE_EQ(pulled, 0.006);
  EXPECT_EQ(tension->cut_mode, kerf::v1::Cutting::PROGRESSIVE);  // the default
  EXPECT_EQ(tension->method, kerf::v1::Integration::IMPLICIT_EULER);
  absl::StatusOr<Scene> deferred = LoadScene("lattice-tension-deferred");
  ASSERT_TRUE(deferred.ok()) << deferred.status();
  EXPECT_EQ(deferred->mesh.tet_count(), 576u);
  EXPECT_EQ(deferred->conditions.prescribed.size(), tension->conditions.prescribed.size());
  EXPECT_EQ(deferred->cut_mode, kerf::v1::Cutting::DEFERRED);
  EXPECT_EQ(deferred->method, kerf::v1::Integration::SYMPLECTIC_EULER);
  absl::StatusOr<Scene> cantilever = LoadScene("bar-cantilever");
  ASSERT_TRUE(cantilever.ok()) << cantilever.status();
  EXPECT_EQ(cantilever->conditions.gravity, Eigen::Vector3d(0, 0, -1));
}

TEST(LoadScene, UnknownNamesAndFilesAreClearErrors) {
  EXPECT_EQ(StatusMessage(LoadScene("liver-cut")),
            "no embedded scene 'liver-cut' (there are: lattice-tension, "
            "lattice-tension-deferred, bar-cantilever)");
}

std::string Tension() { return *EmbeddedSceneText("lattice-tension"); }

TEST(ParseSceneText, UnknownFieldIsAnErrorWithItsPlace) {
  const std::string text = absl::StrReplaceAll(Tension(), {{"poisson_ratio: 0.45", "poisson: 1"}});
  EXPECT_EQ(StatusMessage(ParseSceneText(text, "s.textproto")),
            "s.textproto:13:10: Message type \"kerf.v1.Material\" has no field named \"poisson\".");
}

TEST(ParseSceneText, TwoMeshSourcesAreAnError) {
  const std::string text =
      absl::StrReplaceAll(Tension(), {{"mesh {\n", "mesh {\n  file: \"x.msh\"\n"}});
  EXPECT_EQ(StatusMessage(ParseSceneText(text, "s.textproto")),
            "s.textproto:10:11: Field \"lattice\" is specified along with field \"file\", another "
            "member of oneof \"source\".");
}

TEST(BuildScene, InvalidValuesNameTheSceneAndTheField) {
  const std::pair<std::string, std::string> cases[] = {
      {absl::StrReplaceAll(Tension(), {{"poisson_ratio: 0.45", "poisson_ratio: 0.5"}}),
       "scene 'lattice-tension': material.poisson_ratio must be strictly between -1 and 0.5, "
       "got 0.5"},
      {absl::StrReplaceAll(Tension(), {{"point { y: 0.06 }", "point { y: 0.07 }"}}),
       "scene 'lattice-tension': displacements[1].vertices selects no vertex"},
      {absl::StrReplaceAll(Tension(), {{"cells_x: 4", "cells_x: 0"}}),
       "scene 'lattice-tension': mesh.lattice: cells_x must be in [1, 1024], got 0"},
      {absl::StrReplaceAll(Tension(), {{"normal { y: -1 }", "normal { }"}}),
       "scene 'lattice-tension': displacements[0].vertices.half_space: normal must be non-zero "
       "and finite"},
      {Tension() + "integration { time_step: -1 }\n",
       "scene 'lattice-tension': integration.time_step must be positive (s), or 0 to choose, got "
       "-1"},
      {Tension() + "cutting { mode: 7 }\n",
       "scene 'lattice-tension': cutting.mode must be DEFERRED or PROGRESSIVE, got 7"},
      {Tension() + "cutting { min_temporary_height: -0.01 }\n",
       "scene 'lattice-tension': cutting.min_temporary_height must be a fraction in [0, 1), got "
       "-0.01"},
      {Tension() + "cutting { min_temporary_height: 1 }\n",
       "scene 'lattice-tension': cutting.min_temporary_height must be a fraction in [0, 1), got 1"},
      {Tension() + "cutting { mode: DEFERRED snap_fraction: 0.5 }\n",
       "scene 'lattice-tension': cutting.snap_fraction must be in [0, 0.5), got 0.5"},
      {Tension() + "cutting { snap_fraction: -0.1 }\n",
       "scene 'lattice-tension': cutting.snap_fraction must be in [0, 0.5), got -0.1"},
      {Tension() + "elasticity { model: 9 }\n",
       "scene 'lattice-tension': elasticity.model must be LINEAR, COROTATIONAL or AUTO, got 9"},
      {Tension() + "elasticity { model: AUTO auto_strain: 0 }\n",
       "scene 'lattice-tension': elasticity.auto_strain must be a strain in (0, 1), got 0"},
      {Tension() + "elasticity { model: COROTATIONAL }\nintegration { method: STATIC }\n",
       "scene 'lattice-tension': elasticity.model must be LINEAR for a STATIC scene (the static "
       "solve is linear)"},
      {Tension() + "integration { sleeping { wake_acceleration: 0 } }\n",
       "scene 'lattice-tension': integration.sleeping.wake_acceleration must be positive "
       "(m/s^2), got 0"},
      {Tension() + "integration { sleeping { rest_speed: -1 } }\n",
       "scene 'lattice-tension': integration.sleeping.rest_speed must be a speed >= 0 (m/s), got "
       "-1"},
      {Tension() + "integration { sleeping { quiet_time: nan } }\n",
       "scene 'lattice-tension': integration.sleeping.quiet_time must be a time >= 0 (s), got "
       "nan"},
      {Tension() + "integration { method: SYMPLECTIC_EULER_SUBSTEPPED sleeping { } }\n",
       "scene 'lattice-tension': integration.sleeping needs integration.method SYMPLECTIC_EULER "
       "or IMPLICIT_EULER"},
      {Tension() + "elasticity { model: AUTO }\nintegration { sleeping { } }\n",
       "scene 'lattice-tension': integration.sleeping needs elasticity.model LINEAR (a rotating "
       "law turns every tet each step)"},
      {Tension() + "integration { method: 9 }\n",
       "scene 'lattice-tension': integration.method must be SYMPLECTIC_EULER, "
       "SYMPLECTIC_EULER_SUBSTEPPED, IMPLICIT_EULER or STATIC, got 9"},
      {Tension() + "loads { vertices { ids { ids: 9999 } } total_force { x: 1 } }\n",
       "scene 'lattice-tension': loads[0].vertices.ids: no vertex 9999"},
      {absl::StrReplaceAll(Tension(),
                           {{"lattice { cells_x: 4 cells_y: 6 cells_z: 4 size { x: 0.04 y: 0.06 "
                             "z: 0.04 } }",
                             "file: \"none.msh\""}}),
       "scene 'lattice-tension': ./none.msh: cannot open file"},
  };
  for (const auto& [text, message] : cases) {
    absl::StatusOr<kerf::v1::Scene> spec = ParseSceneText(text, "s.textproto");
    ASSERT_TRUE(spec.ok()) << spec.status();
    EXPECT_EQ(StatusMessage(BuildScene(*spec, ".")), message);
  }
}

TEST(BuildScene, AProgressiveSceneIntegratesImplicitlyUnlessItSaysOtherwise) {
  const auto method_of = [](const std::string& extra) {
    return BuildScene(*ParseSceneText(Tension() + extra, "s.textproto"), ".")->method;
  };
  EXPECT_EQ(method_of(""), kerf::v1::Integration::IMPLICIT_EULER);
  EXPECT_EQ(BuildScene(*ParseSceneText(Tension(), "s.textproto"), ".")->cut_mode,
            kerf::v1::Cutting::PROGRESSIVE);  // a scene that names no mode
  EXPECT_EQ(method_of("cutting { mode: PROGRESSIVE }\n"), kerf::v1::Integration::IMPLICIT_EULER);
  EXPECT_EQ(method_of("integration { method: SYMPLECTIC_EULER }\n"),
            kerf::v1::Integration::SYMPLECTIC_EULER);
  EXPECT_EQ(method_of("cutting { mode: DEFERRED }\n"), kerf::v1::Integration::SYMPLECTIC_EULER);
  EXPECT_EQ(method_of("cutting { mode: DEFERRED }\nintegration { method: IMPLICIT_EULER }\n"),
            kerf::v1::Integration::IMPLICIT_EULER);
}

// A sleeping scene's simulation lets its vertices sleep; setting its state wakes them all.
TEST(Simulation, ASleepingSceneSleepsAtRestAndWakesWhenItsStateIsSet) {
  Scene scene = *BuildScene(
      *ParseSceneText(Tension() + "integration { sleeping { quiet_time: 0.002 } }\n", "s"), ".");
  ASSERT_TRUE(scene.sleep.has_value());
  EXPECT_EQ(scene.sleep->quiet_time, 0.002);
  EXPECT_EQ(scene.sleep->rest_speed, fem::SleepOptions{}.rest_speed);
  std::unique_ptr<Simulation> s = *Simulation::Create(std::move(scene));
  ASSERT_NE(s->sleeping(), nullptr);
  const std::vector<Eigen::Vector3d> settled =
      *fem::SolveStaticEquilibrium(s->model(), s->scene().conditions);
  ASSERT_TRUE(s->SetDisplacement(settled).ok());
  for (int i = 0; i < 5; ++i) s->Step();
  EXPECT_TRUE(s->sleeping()->awake().empty());
  ASSERT_TRUE(s->SetDisplacement(settled).ok());
  EXPECT_EQ(s->sleeping()->awake().size(), s->model().active_vertices().size());
  EXPECT_EQ((*Simulation::Create(*LoadScene("lattice-tension")))->sleeping(), nullptr);
}

// Backward Euler at its automatic step (1 ms) settles where the static solve puts the bar.
TEST(Simulation, ImplicitCantileverSettlesToTheSameDeflection) {
  Scene scene = *LoadScene("bar-cantilever");
  scene.method = kerf::v1::Integration::IMPLICIT_EULER;
  absl::StatusOr<std::unique_ptr<Simulation>> s = Simulation::Create(std::move(scene));
  ASSERT_TRUE(s.ok()) << s.status();
  EXPECT_EQ((*s)->time_step(), Simulation::kImplicitTimeStep);
  for (int step = 0; step < 5000; ++step) (*s)->Step();
  const mesh::VertexId tip_centre = kerf::testing::VertexAt((*s)->mesh(), {5, 0.5, 0.5});
  EXPECT_NEAR(-(*s)->state().displacement[mesh::Index(tip_centre)].z(), 0.06057, 1e-4 * 0.06057);
}

// The cantilever bends 1.2% of its length: the corotational law settles within 0.5% of the
// linear deflection, and rotates (rigid motion is what it removes).
TEST(Simulation, CorotationalCantileverSettlesNearTheLinearDeflection) {
  kerf::v1::Scene spec = *ParseSceneText(*EmbeddedSceneText("bar-cantilever"), "b");
  spec.mutable_integration()->set_method(kerf::v1::Integration::IMPLICIT_EULER);
  spec.mutable_elasticity()->set_model(kerf::v1::Elasticity::COROTATIONAL);
  absl::StatusOr<std::unique_ptr<Simulation>> s = Simulation::Create(*BuildScene(spec, "."));
  ASSERT_TRUE(s.ok()) << s.status();
  for (int step = 0; step < 5000; ++step) (*s)->Step();
  ASSERT_NE((*s)->elastic_forces(), nullptr);
  EXPECT_TRUE((*s)->elastic_forces()->rotating());
  const mesh::VertexId tip_centre = kerf::testing::VertexAt((*s)->mesh(), {5, 0.5, 0.5});
  EXPECT_NEAR(-(*s)->state().displacement[mesh::Index(tip_centre)].z(), 0.06057, 5e-3 * 0.06057);
  EXPECT_NE(-(*s)->state().displacement[mesh::Index(tip_centre)].z(), 0.06057);
}

TEST(Simulation, StaticCantileverReproducesTheReferenceDeflection) {
  kerf::v1::Scene spec = *ParseSceneText(*EmbeddedSceneText("bar-cantilever"), "b");
  spec.mutable_integration()->set_method(kerf::v1::Integration::STATIC);
  absl::StatusOr<std::unique_ptr<Simulation>> s = Simulation::Create(*BuildScene(spec, "."));
  ASSERT_TRUE(s.ok()) << s.status();
  const mesh::VertexId tip_centre = kerf::testing::VertexAt((*s)->mesh(), {5, 0.5, 0.5});
  EXPECT_NEAR(-(*s)->state().displacement[mesh::Index(tip_centre)].z(), 0.06057, 5e-6);
  // The mesh's current positions follow the displacement.
  EXPECT_EQ(
      (*s)->mesh().current_position(tip_centre),
      (*s)->mesh().rest_position(tip_centre) + (*s)->state().displacement[mesh::Index(tip_centre)]);
}

TEST(Simulation, ExplicitCantileverSettlesToTheSameDeflection) {
  absl::StatusOr<std::unique_ptr<Simulation>> s = Simulation::Create(*LoadScene("bar-cantilever"));
  ASSERT_TRUE(s.ok()) << s.status();
  EXPECT_NEAR((*s)->time_step(), 0.9 * (*s)->critical_time_step(), 1e-15);
  for (int step = 0; step < 20000; ++step) (*s)->Step();
  const mesh::VertexId tip_centre = kerf::testing::VertexAt((*s)->mesh(), {5, 0.5, 0.5});
  EXPECT_NEAR(-(*s)->state().displacement[mesh::Index(tip_centre)].z(), 0.06057, 1e-4 * 0.06057);
}

// In sub-steps, the explicit cantilever keeps the haptic step (1 ms) and settles where the
// static solve puts it.
TEST(Simulation, SubsteppedCantileverKeepsTheHapticStepAndSettles) {
  Scene scene = *LoadScene("bar-cantilever");
  scene.method = kerf::v1::Integration::SYMPLECTIC_EULER_SUBSTEPPED;
  absl::StatusOr<std::unique_ptr<Simulation>> s = Simulation::Create(std::move(scene));
  ASSERT_TRUE(s.ok()) << s.status();
  EXPECT_EQ((*s)->time_step(), Simulation::kImplicitTimeStep);
  for (int step = 0; step < 40000; ++step) (*s)->Step();
  EXPECT_GE((*s)->last_sub_steps(), 1);
  const mesh::VertexId tip_centre = kerf::testing::VertexAt((*s)->mesh(), {5, 0.5, 0.5});
  EXPECT_NEAR(-(*s)->state().displacement[mesh::Index(tip_centre)].z(), 0.06057, 1e-4 * 0.06057);
}

TEST(Simulation, StaticSceneThatIsNotHeldIsRefused) {
  kerf::v1::Scene spec = *ParseSceneText(*EmbeddedSceneText("bar-cantilever"), "b");
  spec.clear_displacements();
  spec.mutable_integration()->set_method(kerf::v1::Integration::STATIC);
  EXPECT_EQ(StatusMessage(Simulation::Create(*BuildScene(spec, "."))),
            "the stiffness is singular: the body can move rigidly; hold it with prescribed "
            "displacements");
}

}  // namespace
}  // namespace kerf::sim
