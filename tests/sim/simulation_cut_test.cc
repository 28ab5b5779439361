// Cutting a simulated body: the elastic model follows the cut, and a piece cut free falls.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "fem/tensor_mass_model.h"
#include "mesh/connected_components.h"
#include "mesh/mesh_validation.h"
#include "sim/scene.h"
#include "sim/simulation.h"
#include "support/held_bar_scene.h"

namespace kerf::sim {
namespace {

using kerf::testing::kHeldBarScene;

TEST(Simulation, APieceCutFreeFallsAndTheModelFollowsTheCut) {
  std::unique_ptr<Simulation> s =
      *Simulation::Create(*BuildScene(*ParseSceneText(kHeldBarScene, "held-bar"), "."));
  double mass_before = 0;
  for (const double m : s->model().masses()) mass_before += m;
  for (int step = 0; step < 100; ++step) s->Step();
  // Cut through the whole depth at x = 33.7 mm (on the deformed shape), sweeping along y.
  double time = 0;
  for (int k = 0; k <= 15; ++k) {
    const Eigen::Vector3d tip(0.0337, -0.005 + 0.002 * k, -0.03);
    ASSERT_TRUE(s->ApplyBladePose({time, tip, tip + Eigen::Vector3d(0, 0, 0.06)}).ok());
    time += 0.01;
  }
  ASSERT_TRUE(s->WithdrawBlade().ok());
  const cut::CutStatistics& cut = s->cutter()->statistics();
  std::printf("cut %zu tets into %zu\n", cut.cut_tets, cut.new_tets);
  const mesh::MeshComponents pieces = mesh::FindConnectedComponents(s->mesh());
  ASSERT_EQ(pieces.count, 2u);
  EXPECT_TRUE(mesh::FindMeshDefects(s->mesh()).empty());

  // The incremental model equals one built from scratch, and keeps the mass.
  const fem::TensorMassModel rebuilt =
      *fem::TensorMassModel::Create(s->mesh(), s->scene().material);
  double mass_after = 0;
  for (const double m : s->model().masses()) mass_after += m;
  EXPECT_NEAR(mass_after, mass_before, 1e-12 * mass_before);
  for (const mesh::VertexId v : s->mesh().vertices()) {
    EXPECT_NEAR(s->model().mass(v), rebuilt.mass(v), 1e-12 * mass_before);
    EXPECT_LE((s->model().vertex_tensor(v) - rebuilt.vertex_tensor(v)).norm(),
              1e-9 * rebuilt.vertex_tensor(v).norm() + 1e-12);
  }
  ASSERT_EQ(s->model().edges().size(), rebuilt.edges().size());

  // 0.1 s later the free piece has fallen (free fall with damping 5/s: about 4 cm), while the
  // held piece hangs where it was.
  const double cut_time = s->state().time;
  while (s->state().time < cut_time + 0.1) s->Step();
  const std::int32_t held_piece = pieces.tet_component[mesh::Index(*s->mesh().tets().begin())];
  double free_drop = 0, held_drop = 0;
  int free_count = 0, held_count = 0;
  for (const mesh::TetId t : s->mesh().tets()) {
    const bool held = pieces.tet_component[mesh::Index(t)] == held_piece;
    for (const mesh::VertexId v : s->mesh().tet(t)) {
      const double dz = s->state().displacement[mesh::Index(v)].z();
      (held ? held_drop : free_drop) += dz;
      ++(held ? held_count : free_count);
    }
  }
  free_drop /= free_count;
  held_drop /= held_count;
  std::printf("0.1 s after the cut: free piece moved %.4f m in z, held piece %.4f m\n", free_drop,
              held_drop);
  EXPECT_LT(free_drop, -0.03) << "the free piece did not fall";
  EXPECT_GT(held_drop, -0.015) << "the held piece fell";
  EXPECT_TRUE(std::isfinite(free_drop) && std::isfinite(held_drop));
}

// Cutting the lattice while it still moves under its load drops hits (issue 5 is to fix that);
// the vertices the cutter made and removed again still have slots, and the model and the state
// must cover every slot of the mesh after every pose, or the forces of the next frame are read
// past the end.
TEST(Simulation, TheStateCoversEveryVertexSlotWhenACutDropsItsHits) {
  std::unique_ptr<Simulation> s = *Simulation::Create(*LoadScene("lattice-tension"));
  double time = 0;
  for (int k = 0; k <= 25; ++k) {
    const Eigen::Vector3d tip(-0.005 + 0.002 * k, 0.0385, -0.005);
    ASSERT_TRUE(s->ApplyBladePose({time, tip, tip + Eigen::Vector3d(0, 0, 0.05)}).ok());
    ASSERT_EQ(s->state().displacement.size(), s->mesh().vertex_index_bound()) << "pose " << k;
    for (int step = 0; step < 10; ++step) s->Step();
    time += 0.01;
  }
  ASSERT_TRUE(s->WithdrawBlade().ok());
  EXPECT_EQ(s->state().displacement.size(), s->mesh().vertex_index_bound());
  EXPECT_EQ(s->state().velocity.size(), s->mesh().vertex_index_bound());
  EXPECT_EQ(s->model().vertex_count(), s->mesh().vertex_index_bound());
  EXPECT_TRUE(mesh::FindMeshDefects(s->mesh()).empty());
}

// The model equals one built afresh from the mesh (with the same soft tets).
void ExpectModelFollowsMesh(const Simulation& s) {
  const fem::TensorMassModel rebuilt = *fem::TensorMassModel::Create(
      s.mesh(), s.scene().material,
      [&](mesh::TetId t) { return s.cutter() == nullptr ? 1.0 : s.cutter()->StiffnessScale(t); });
  for (const mesh::VertexId v : s.mesh().vertices()) {
    ASSERT_NEAR(s.model().mass(v), rebuilt.mass(v), 1e-9 * rebuilt.mass(v) + 1e-15);
    ASSERT_LE((s.model().vertex_tensor(v) - rebuilt.vertex_tensor(v)).norm(),
              1e-9 * rebuilt.vertex_tensor(v).norm() + 1e-12);
  }
  ASSERT_EQ(s.model().edges().size(), rebuilt.edges().size());
}

// A blade that hesitates (two steps of 1 mm on, one of 0.5 mm back) and wavers, one physics
// step between poses, then is withdrawn halfway: some poses only swap tets among vertices
// already made (a case rebuilt, temporary tets made final), and the model must follow those
// too.
TEST(Simulation, TheModelFollowsPosesThatMakeNoVertex) {
  kerf::v1::Scene spec = *ParseSceneText(*EmbeddedSceneText("lattice-tension"), "tension");
  spec.mutable_cutting()->set_mode(kerf::v1::Cutting::PROGRESSIVE);
  std::unique_ptr<Simulation> s = *Simulation::Create(*BuildScene(spec, "."));
  double x = -0.005;
  for (int k = 0; k < 60; ++k) {
    x += k % 3 == 2 ? -0.0005 : 0.001;
    const Eigen::Vector3d tip(x, 0.0385 + 0.002 * std::sin(0.3 * k + 17), 0.008);
    ASSERT_TRUE(s->ApplyBladePose({0.001 * k, tip, tip + Eigen::Vector3d(0, 0, 0.05)}).ok());
    SCOPED_TRACE(k);
    ExpectModelFollowsMesh(*s);
    s->Step();
  }
  ASSERT_TRUE(s->WithdrawBlade().ok());
  ExpectModelFollowsMesh(*s);
  EXPECT_GT(s->cutter()->statistics().cut_tets, 0u);
}

// Progressive cutting through the lattice while it still moves under its load (every pose 10
// physics steps later): the model follows every temporary change incrementally (it equals one
// built afresh after every pose, and no vertex left behind keeps a rounding of mass, which
// made the critical step 0). Both modes find where the moving tissue met the blade between
// poses: each cuts every tet of the cross-section (96), with no more new tets per cut tet than
// the paper's 5.2; progressively the bar is cut through. (Deferred, the bar springing into
// tension while it is cut leaves four faces near its far corner uncut: docs/cutting-fidelity.md.)
TEST(Simulation, ProgressiveCuttingFollowsMovingTissueIncrementally) {
  for (const bool progressive : {true, false}) {
    SCOPED_TRACE(progressive ? "progressive" : "deferred");
    kerf::v1::Scene spec = *ParseSceneText(*EmbeddedSceneText("lattice-tension"), "tension");
    spec.mutable_cutting()->set_mode(progressive ? kerf::v1::Cutting::PROGRESSIVE
                                                 : kerf::v1::Cutting::DEFERRED);
    std::unique_ptr<Simulation> s = *Simulation::Create(*BuildScene(spec, "."));
    double time = 0;
    for (int k = 0; k <= 25; ++k) {
      const Eigen::Vector3d tip(-0.005 + 0.002 * k, 0.0385, -0.005);
      ASSERT_TRUE(s->ApplyBladePose({time, tip, tip + Eigen::Vector3d(0, 0, 0.05)}).ok());
      if (progressive) {
        SCOPED_TRACE(k);
        ExpectModelFollowsMesh(*s);
        if (::testing::Test::HasFatalFailure()) return;
      }
      for (int step = 0; step < 10; ++step) s->Step();
      time += 0.01;
    }
    ASSERT_TRUE(s->WithdrawBlade().ok());
    EXPECT_TRUE(mesh::FindMeshDefects(s->mesh()).empty());
    if (progressive) {
      EXPECT_EQ(mesh::FindConnectedComponents(s->mesh()).count, 2u);
    }
    EXPECT_EQ(s->cutter()->statistics().cut_tets, 96u);
    EXPECT_LE(s->mesh().tet_count() - (576u - 96u), 5.2 * 96);
  }
}

// A split adds no energy: the points it makes, and the copies parting makes of them, take the
// displacement and velocity of the side they are on, so the strain in each piece is the strain
// of the tet it came from. The lattice pulled into tension, cut deferred through while it moves
// (10 physics steps between poses): the mechanical energy right after each pose is what it was
// right before. (Progressively the points on the blade move with it, reshaping their pieces at
// rest: that changes the energy, by 2% at most in the live-cut experiment.)
TEST(Simulation, ASplitAddsNoEnergy) {
  for (const char* law : {"", "elasticity { model: COROTATIONAL }\n"}) {
    SCOPED_TRACE(law);
    kerf::v1::Scene spec = *ParseSceneText(
        *EmbeddedSceneText("lattice-tension") + "cutting { mode: DEFERRED }\n" + law, "tension");
    std::unique_ptr<Simulation> s = *Simulation::Create(*BuildScene(spec, "."));
    double time = 0;
    for (int k = 0; k <= 25; ++k) {
      const Eigen::Vector3d tip(-0.005 + 0.002 * k, 0.0385, -0.005);
      const double before = s->MechanicalEnergy();
      ASSERT_TRUE(s->ApplyBladePose({time, tip, tip + Eigen::Vector3d(0, 0, 0.05)}).ok());
      EXPECT_LE(s->MechanicalEnergy(), before * (1 + 1e-9) + 1e-15) << "pose " << k;
      for (int step = 0; step < 10; ++step) s->Step();
      time += 0.01;
    }
    const double before = s->MechanicalEnergy();
    ASSERT_TRUE(s->WithdrawBlade().ok());
    EXPECT_LE(s->MechanicalEnergy(), before * (1 + 1e-9) + 1e-15);
  }
}

// Snapping (deferred): a cut through the sagging bar 0.5 mm past the plane of vertices x = 30 mm
// (at rest) goes through them. Each copy starts where its vertex is and moves as it does; the
// model follows; the cut-off end falls as a piece cut along the blade does.
TEST(Simulation, ASnappedCutGoesThroughVerticesAndTheCopiesStartWithTheirState) {
  std::unique_ptr<Simulation> s = *Simulation::Create(*BuildScene(
      *ParseSceneText(std::string(kHeldBarScene) + "cutting { mode: DEFERRED snap_fraction: 0.2 }",
                      "held-bar"),
      "."));
  for (int step = 0; step < 100; ++step) s->Step();
  const std::uint32_t original_vertices = s->mesh().vertex_index_bound();
  double time = 0;
  for (int k = 0; k <= 15; ++k) {
    const Eigen::Vector3d tip(0.0305, -0.005 + 0.002 * k, -0.03);
    ASSERT_TRUE(s->ApplyBladePose({time, tip, tip + Eigen::Vector3d(0, 0, 0.06)}).ok());
    time += 0.01;
  }
  ASSERT_TRUE(s->WithdrawBlade().ok());
  const cut::CutStatistics& cut = s->cutter()->statistics();
  EXPECT_EQ(cut.snapped_vertices, 9u);
  EXPECT_EQ(cut.new_tets, cut.cut_tets);  // every cut tet went over whole
  EXPECT_EQ(mesh::FindConnectedComponents(s->mesh()).count, 2u);
  ExpectModelFollowsMesh(*s);
  int copies = 0;
  for (const mesh::VertexId copy : s->mesh().vertices()) {
    if (mesh::Index(copy) < original_vertices) continue;
    ++copies;
    const Eigen::Vector3d& rest = s->mesh().rest_position(copy);
    EXPECT_NEAR(rest.x(), 0.03, 1e-15);
    for (const mesh::VertexId v : s->mesh().vertices()) {
      if (mesh::Index(v) < original_vertices && s->mesh().rest_position(v) == rest) {
        EXPECT_EQ(s->state().displacement[mesh::Index(copy)],
                  s->state().displacement[mesh::Index(v)]);
        EXPECT_EQ(s->state().velocity[mesh::Index(copy)], s->state().velocity[mesh::Index(v)]);
      }
    }
  }
  EXPECT_EQ(copies, 9);
  const double cut_time = s->state().time;
  while (s->state().time < cut_time + 0.1) s->Step();
  double far_end_drop = 0;
  for (const mesh::VertexId v : s->mesh().vertices()) {
    if (s->mesh().rest_position(v).x() > 0.055) {
      far_end_drop = std::min(far_end_drop, s->state().displacement[mesh::Index(v)].z());
    }
  }
  std::printf("0.1 s after the snapped cut the far end moved %.4f m in z\n", far_end_drop);
  EXPECT_LT(far_end_drop, -0.03) << "the cut-off end did not fall";
}

TEST(Simulation, ABadBladePoseChangesNothing) {
  std::unique_ptr<Simulation> s =
      *Simulation::Create(*BuildScene(*ParseSceneText(kHeldBarScene, "held-bar"), "."));
  ASSERT_TRUE(s->ApplyBladePose({0, {0.0337, -0.005, -0.03}, {0.0337, -0.005, 0.03}}).ok());
  const mesh::ChangeMark mark = s->mesh().change_log().Mark();
  EXPECT_EQ(s->ApplyBladePose({0, {0.0337, 0.005, -0.03}, {0.0337, 0.005, 0.03}}).code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(s->mesh().change_log().Mark(), mark);
}

}  // namespace
}  // namespace kerf::sim
