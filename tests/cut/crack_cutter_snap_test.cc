// Snapping (cut/crack_cutter_snap.cc): where crossings are taken at corners, where they move away
// from them, and what keeps a cut from being lost on the tissue's surface or cutting a tet free.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "cut/crack_cutter.h"
#include "cut/cut_statistics.h"
#include "lab/crack_fidelity.h"
#include "mesh/box_lattice.h"
#include "mesh/connected_components.h"
#include "mesh/mesh_quality.h"
#include "mesh/mesh_validation.h"
#include "support/unit_tet.h"

namespace kerf::cut {
namespace {

using mesh::TetMesh;

// A second pass beside the first, 0.12 away across pieces whose edges are half the tissue's:
// its crossings are within the snap fraction of the tissue's edges of the first crack's points
// (though not of the pieces' edges), so they snap onto them and make no pieces finer than a cut
// through whole tets would.
TEST(CrackCutter, CutsThroughPiecesSnapAsFarAsThroughTheirTet) {
  TetMesh m = kerf::testing::UnitTet();
  CrackCutter cutter = *CrackCutter::Create(
      &m, 1, {.max_length = 10, .max_step = 10, .max_speed = 100}, {.mode = CutMode::kDeferred});
  // The plane x = 0.5 swept upwards cuts corner 1 off at its edges' middles.
  ASSERT_TRUE(cutter.ApplyPose({0, {0.5, -1, -1}, {0.5, 2, -1}}).ok());
  ASSERT_TRUE(cutter.ApplyPose({1, {0.5, -1, 2}, {0.5, 2, 2}}).ok());
  ASSERT_TRUE(cutter.ApplyPose({2, {0.62, -1, 2}, {0.62, 2, 2}}).ok());  // above the tet
  const std::size_t tets = m.tet_count(), vertices = m.vertex_count();
  ASSERT_GT(tets, 1u);
  // The plane x = 0.62 swept downwards crosses the corner's edges 0.24 of their pieces' length
  // from the first points.
  ASSERT_TRUE(cutter.ApplyPose({3, {0.62, -1, -1}, {0.62, 2, -1}}).ok());
  cutter.Finish();
  EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
  EXPECT_EQ(m.tet_count(), tets);
  EXPECT_EQ(m.vertex_count(), vertices);
  EXPECT_EQ(mesh::FindConnectedComponents(m).count, 2u);
}

// A blade sweeping the plane 0.27 of the way up edge 0-1, in a tet whose corners 0 and 1 stand
// 45 degrees apart as seen from edge 2-3 (its dihedral angle there): the crossing makes a point
// there and the tet is cut. Its bottom corners 2 and 3 lie within the snap band of the blade but
// 0.47 from where it comes in through the tet's sides (every face is the tissue's surface):
// snapped, they would move the crack's rim that far, so they stay off it. At 17 degrees a tet
// bisected at that point would leave a half of 4.6 degrees, and the crossing would be taken at
// corner 0; but that tet is so flat that the blade sweeps along its bottom face, which lies on the
// tissue's surface, 0.08 of its mean edge above it: snapped, its corners would lay the crack on the
// surface and nothing be cut. They stay off it (the crossing near corner 0 moves away from it
// instead) and the skin under the blade is cut. Either way all the blade swept is covered, no piece
// under 5 degrees.
TEST(CrackCutter, ACrossingThatWouldLeaveASliverSnapsToItsCorner) {
  for (const double height : {0.3, 1.0}) {
    SCOPED_TRACE(::testing::Message() << "corner 1 at height " << height);
    TetMesh m;
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 0, height),
                                     Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, -1, 0)}) {
      m.AddVertex(p);
    }
    ASSERT_TRUE(
        m.AddTet({mesh::VertexId(0), mesh::VertexId(1), mesh::VertexId(2), mesh::VertexId(3)})
            .ok());
    const TetMesh tissue = m;
    CrackCutter cutter =
        *CrackCutter::Create(&m, 1, {.max_length = 10, .max_step = 10, .max_speed = 100});
    const double z = 0.27 * height;
    const BladePose from{0, {-1, -2, z}, {3, -2, z}}, to{0.1, {-1, 2, z}, {3, 2, z}};
    ASSERT_TRUE(cutter.ApplyPose(from).ok());
    ASSERT_TRUE(cutter.ApplyPose(to).ok());
    cutter.Finish();
    ASSERT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
    const bool point_on_edge = std::any_of(m.vertices().begin(), m.vertices().end(), [&](auto v) {
      return (m.rest_position(v) - Eigen::Vector3d(1, 0, z)).norm() < 1e-12;
    });
    EXPECT_EQ(point_on_edge, height == 1.0);
    EXPECT_LT(cutter.statistics().snapped_vertices, 3u);  // the bottom face stays off the crack
    EXPECT_EQ(cutter.statistics().cut_tets, 1u);
    lab::FidelityMeter meter(tissue);
    meter.AddStep(from, to);
    const lab::Fidelity f = meter.Measure(meter.FindCrack(m));
    EXPECT_EQ(f.coverage, 1);
    EXPECT_EQ(f.overcut_faces, 0u);
    EXPECT_GE(mesh::MeasureMeshQuality(m).min_dihedral_deg, 5);
  }
}

// A tet whose edges 0-1 and 0-2 meet at corner 0 at about 12 degrees, cut by the plane z = 0.27,
// 0.27 of both edges up from corner 0, beyond the snap share. Bisecting the tet at edge 0-1's
// crossing would leave a half under 5 degrees, so corner 0 is snapped onto the crack; bisecting
// it at edge 0-2's would not, and a point kept there would make a 12-degree triangle with the
// snapped corner and three pieces under 5 degrees. Near a thin corner, that crossing is taken at
// the corner too: one tet cut, no piece under 5 degrees.
TEST(CrackCutter, ACrossingNearAThinCornerSnapsToIt) {
  TetMesh m;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 0, 1),
                                   Eigen::Vector3d(0.8, 0.05, 1), Eigen::Vector3d(0, -1, -0.5)}) {
    m.AddVertex(p);
  }
  ASSERT_TRUE(
      m.AddTet({mesh::VertexId(0), mesh::VertexId(1), mesh::VertexId(2), mesh::VertexId(3)}).ok());
  CrackCutter cutter =
      *CrackCutter::Create(&m, 1, {.max_length = 10, .max_step = 10, .max_speed = 100});
  ASSERT_TRUE(cutter.ApplyPose({0, {-1, -2, 0.27}, {3, -2, 0.27}}).ok());
  ASSERT_TRUE(cutter.ApplyPose({0.1, {-1, 2, 0.27}, {3, 2, 0.27}}).ok());
  cutter.Finish();
  ASSERT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
  EXPECT_EQ(cutter.statistics().cut_tets, 1u);
  const Eigen::Vector3d on_edge_0_2 =
      Eigen::Vector3d(1, 0, 0) + 0.27 * Eigen::Vector3d(-0.2, 0.05, 1);
  EXPECT_FALSE(std::any_of(m.vertices().begin(), m.vertices().end(), [&](auto v) {
    return (m.rest_position(v) - on_edge_0_2).norm() < 1e-12;
  }));
  EXPECT_EQ(mesh::MeasureMeshQuality(m).slivers, 0u);
}

// A tet whose edges from corner 1 to corners 0 and 2 meet there at about 9 degrees, cut three
// times by a vertical blade: across at x = 0.05 (corners 0 and 2 snap onto the crack) and at
// x = 0.3 (a point on edge 0-1), then, at x = 0.6, in from under edge 0-1, back onto it and along
// it towards corner 1 to x = 0.78, where it leaves. The crack's front advanced along the edge,
// from its point at x = 0.3 to where the blade left it, 0.31 of the edge's piece from corner 1:
// too far from the blade's last step for corner 1 to snap, and a point kept there makes a piece
// of 3.7 degrees. It moves off the thin corner instead, as a crossing the blade swept would.
TEST(CrackCutter, ACrackAdvancingAlongAnEdgeStopsShortOfAThinCorner) {
  TetMesh m;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0.05, 0),
                                   Eigen::Vector3d(0, 0.15, 0), Eigen::Vector3d(0.6, 0.08, 0.5)}) {
    m.AddVertex(p);
  }
  ASSERT_TRUE(
      m.AddTet({mesh::VertexId(0), mesh::VertexId(1), mesh::VertexId(2), mesh::VertexId(3)}).ok());
  CrackCutter cutter =
      *CrackCutter::Create(&m, 1, {.max_length = 10, .max_step = 10, .max_speed = 100});
  // The blade stands upright at (x, y), through the tet's height; it moves 0.02 a pose.
  const std::vector<Eigen::Vector2d> corners = {{0.05, -0.3}, {0.05, 0.5},   {0.3, 0.5},
                                                {0.3, -0.3},  {0.6, -0.3},   {0.6, 0.06},
                                                {0.6, 0.03},  {0.78, 0.039}, {0.78, -0.3}};
  double time = 0;
  const auto pose_at = [&](const Eigen::Vector2d& at) {
    time += 0.01;
    return cutter.ApplyPose({time, {at.x(), at.y(), -0.5}, {at.x(), at.y(), 1.2}});
  };
  ASSERT_TRUE(pose_at(corners[0]).ok());
  for (std::size_t i = 1; i < corners.size(); ++i) {
    const Eigen::Vector2d move = corners[i] - corners[i - 1];
    const int steps = std::max(1, static_cast<int>(move.cwiseAbs().maxCoeff() / 0.02));
    for (int k = 1; k <= steps; ++k) {
      ASSERT_TRUE(pose_at(corners[i - 1] + move * k / steps).ok());
    }
  }
  cutter.Finish();
  ASSERT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
  EXPECT_EQ(cutter.statistics().cut_tets, 1u);
  EXPECT_EQ(mesh::MeasureMeshQuality(m).slivers, 0u);
}

// A tet with three short edges at one end and three long ones to its far corner (mean edge
// 1.67): the plane x = 0.45 crosses the long edges 0.15 of their length from the short end, within
// the snap fraction (0.2), but its corners there lie 0.27 of the tet's mean edge from the plane.
// Snapped onto the crack, the crack would be their face, 0.27 l from where the blade went (and
// on the tissue's surface: nothing cut). Instead the points move away from them, no farther from
// the blade's path than a quarter of the mean edge: the tip is cut off, every sample covered and
// no crack face overcut.
TEST(CrackCutter, AVertexFarFromTheBladeInItsTetsIsNotSnappedOntoTheCrack) {
  for (const CutMode mode : {CutMode::kProgressive, CutMode::kDeferred}) {
    SCOPED_TRACE(mode == CutMode::kProgressive ? "progressive" : "deferred");
    TetMesh m;
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3, 0, 0),
                                     Eigen::Vector3d(0, 0.3, 0), Eigen::Vector3d(0, 0, 0.3)}) {
      m.AddVertex(p);
    }
    ASSERT_TRUE(
        m.AddTet({mesh::VertexId(0), mesh::VertexId(1), mesh::VertexId(2), mesh::VertexId(3)})
            .ok());
    const TetMesh tissue = m;
    CrackCutter cutter =
        *CrackCutter::Create(&m, mesh::MeanEdgeLength(m),
                             {.max_length = 10, .max_step = 10, .max_speed = 100}, {.mode = mode});
    lab::FidelityMeter meter(tissue);
    const BladePose from{0, {0.45, -1, -1}, {0.45, 2, -1}}, to{0.1, {0.45, -1, 2}, {0.45, 2, 2}};
    ASSERT_TRUE(cutter.ApplyPose(from).ok());
    ASSERT_TRUE(cutter.ApplyPose(to).ok());
    cutter.Finish();
    meter.AddStep(from, to);
    ASSERT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
    EXPECT_EQ(mesh::FindConnectedComponents(m).count, 2u);
    EXPECT_EQ(cutter.statistics().snapped_vertices, 0u);
    const lab::Fidelity f = meter.Measure(meter.FindCrack(m));
    EXPECT_GT(f.samples, 0u);
    EXPECT_EQ(f.coverage, 1);
    EXPECT_EQ(f.overcut_faces, 0u);
  }
}

// Six times the rest volume of `t`, signed.
double OrientedVolume(const TetMesh& m, const mesh::TetVertices& t) {
  const Eigen::Vector3d a = m.rest_position(t[0]);
  return (m.rest_position(t[1]) - a)
      .cross(m.rest_position(t[2]) - a)
      .dot(m.rest_position(t[3]) - a);
}

// Adds a tet over face `face` of tet 0, its apex `height` off the face's middle on the side away
// from corner `away`.
void AddTetBeside(TetMesh* m, const std::array<int, 3>& face, int away, double height) {
  const auto at = [&](int i) { return m->rest_position(mesh::VertexId(i)); };
  const Eigen::Vector3d normal =
      (at(face[1]) - at(face[0])).cross(at(face[2]) - at(face[0])).normalized();
  const double side = normal.dot(at(away) - at(face[0])) > 0 ? -1 : 1;
  const mesh::VertexId apex =
      m->AddVertex((at(face[0]) + at(face[1]) + at(face[2])) / 3 + side * height * normal);
  mesh::TetVertices t = {mesh::VertexId(face[0]), mesh::VertexId(face[1]), mesh::VertexId(face[2]),
                         apex};
  if (OrientedVolume(*m, t) < 0) std::swap(t[0], t[1]);
  ASSERT_TRUE(m->AddTet(t).ok());
}

// Sweeps a blade lying in the plane z = 0 across `m` from x = -1 to x = `far` (its ends at y = -1
// and y = `far`), withdraws it and checks the mesh; returns the vertices snapped onto the crack.
std::size_t SweepThePlaneZ0(TetMesh* m, double far) {
  CrackCutter cutter = *CrackCutter::Create(m, mesh::MeanEdgeLength(*m),
                                            {.max_length = 10, .max_step = 10, .max_speed = 100});
  EXPECT_TRUE(cutter.ApplyPose({0, {-1, -1, 0}, {-1, far, 0}}).ok());
  EXPECT_TRUE(cutter.ApplyPose({0.1, {far, -1, 0}, {far, far, 0}}).ok());
  cutter.Finish();
  EXPECT_TRUE(mesh::FindMeshDefects(*m).empty()) << mesh::ValidateMesh(*m);
  return cutter.statistics().snapped_vertices;
}

// A flat tet, two corners 0.005 below the plane z = 0 and two 0.005 above, swept by a blade in
// that plane: every corner lies on the blade's path to the least snapping (so the tissue's surface
// keeps none off the crack), and all four snap, which puts every face of it on the crack: a chip.
// Held below by a tet beside face 0-1-3, it holds by that face (kept off the crack): no chip is
// cut free. Alone, it has no face to hold by, and the whole mesh is it.
TEST(CrackCutter, ATetWithEveryCornerOnTheCrackHoldsByAFaceOffIt) {
  for (const bool held : {true, false}) {
    SCOPED_TRACE(held ? "held below" : "alone");
    TetMesh m;
    const std::array<Eigen::Vector3d, 4> flat = {
        Eigen::Vector3d(0, 0, -0.005), Eigen::Vector3d(1, 0, 0.005), Eigen::Vector3d(0, 1, 0.005),
        Eigen::Vector3d(1, 1, -0.005)};
    for (const Eigen::Vector3d& p : flat) m.AddVertex(p);
    ASSERT_TRUE(
        m.AddTet({mesh::VertexId(0), mesh::VertexId(1), mesh::VertexId(2), mesh::VertexId(3)})
            .ok());
    if (held) AddTetBeside(&m, {0, 1, 3}, 2, 1);
    EXPECT_EQ(SweepThePlaneZ0(&m, 2), 4u);
    EXPECT_EQ(mesh::FindConnectedComponents(m).count, 1u);
  }
}

// Two flat tets side by side (sharing face 1-2-3), every corner within 0.005 of the plane z = 0
// a blade sweeps: all five snap, and each tet is a chip of its own, the one beside the other.
// The first holds by the tet below it (a corner off the crack), the second by the first: one
// piece, nothing cut free.
TEST(CrackCutter, ChipsSideBySideHoldByEachOther) {
  TetMesh m;
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0, 0, -0.005), Eigen::Vector3d(1, 0, 0.005), Eigen::Vector3d(0, 1, 0.005),
        Eigen::Vector3d(1, 1, -0.005), Eigen::Vector3d(1.6, 1.6, 0.005)}) {
    m.AddVertex(p);
  }
  for (const mesh::TetVertices& t : {mesh::TetVertices{mesh::VertexId(0), mesh::VertexId(1),
                                                       mesh::VertexId(2), mesh::VertexId(3)},
                                     mesh::TetVertices{mesh::VertexId(1), mesh::VertexId(2),
                                                       mesh::VertexId(3), mesh::VertexId(4)}}) {
    mesh::TetVertices oriented = t;
    if (OrientedVolume(m, oriented) < 0) std::swap(oriented[0], oriented[1]);
    ASSERT_TRUE(m.AddTet(oriented).ok());
  }
  AddTetBeside(&m, {0, 1, 3}, 2, 1);
  EXPECT_EQ(SweepThePlaneZ0(&m, 3), 5u);
  EXPECT_EQ(mesh::FindConnectedComponents(m).count, 1u);
}

// Cuts `tissue` along `poses` in `mode` (cell size 1) and withdraws the blade: the mesh valid, the
// crack's fidelity to the path, and the cutter's counts.
struct LatticeCut {
  lab::Fidelity fidelity;
  CutStatistics statistics;
};
void CutAlong(const TetMesh& tissue, const std::vector<BladePose>& poses, CutMode mode,
              LatticeCut* cut) {
  TetMesh m = tissue;
  CrackCutter cutter = *CrackCutter::Create(
      &m, 1, {.max_length = 10, .max_step = 10, .max_speed = 1000}, {.mode = mode});
  lab::FidelityMeter meter(tissue);
  for (std::size_t k = 0; k < poses.size(); ++k) {
    ASSERT_TRUE(cutter.ApplyPose(poses[k]).ok()) << "pose " << k;
    if (k > 0) meter.AddStep(poses[k - 1], poses[k]);
  }
  cutter.Finish();
  ASSERT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
  cut->fidelity = meter.Measure(meter.FindCrack(m));
  cut->statistics = cutter.statistics();
}

// A blade runs with its tip along a line of vertices inside a lattice (y = 2, z = 1) out to its
// side x = 0, slides along that side (cutting nothing) to the vertices at y = 1, and leaves. The
// vertices at both ends of the slide are on the crack, from parts of the path a cell apart; the
// edges and faces between them (the diagonals of the corner column) are not: no crack face lies
// farther from the swept surface than the meter's tolerance.
TEST(CrackCutter, VerticesTheBladeReachedApartDoNotJoinOnTheCrack) {
  std::vector<Eigen::Vector2d> path;
  for (int k = 0; k <= 50; ++k) path.emplace_back(2.5 - 0.05 * k, 2);
  for (int k = 1; k <= 20; ++k) path.emplace_back(0, 2 - 0.05 * k);
  for (int k = 1; k <= 6; ++k) path.emplace_back(-0.05 * k, 1 - 0.02 * k);
  std::vector<BladePose> poses;
  for (std::size_t k = 0; k < path.size(); ++k) {
    poses.push_back({0.01 * static_cast<double>(k),
                     {path[k].x(), path[k].y(), 1},
                     {path[k].x(), path[k].y(), 2.8}});
  }
  for (const CutMode mode : {CutMode::kProgressive, CutMode::kDeferred}) {
    SCOPED_TRACE(mode == CutMode::kProgressive ? "progressive" : "deferred");
    LatticeCut cut;
    ASSERT_NO_FATAL_FAILURE(CutAlong(
        *mesh::MakeBoxLattice({.cells_x = 2, .cells_y = 3, .cells_z = 2}), poses, mode, &cut));
    EXPECT_GT(cut.fidelity.crack_faces, 0u);
    EXPECT_GE(cut.fidelity.coverage, 0.99);
    EXPECT_EQ(cut.fidelity.overcut_faces, 0u);
  }
}

// A blade grazing the tissue: its tip 0.05 of an edge under the top of a lattice, sweeping
// across it; or lying flat 0.1 under the top, shaving it. The vertices of the top lie within the
// snap band of the blade's path; snapped onto the crack, they would lay it on the surface and
// nothing would be cut. They stay off it, and the crack covers every sample of the swept surface.
TEST(CrackCutter, ABladeGrazingTheSurfaceCutsTheSkinUnderIt) {
  for (const bool flat : {false, true}) {
    std::vector<BladePose> poses;
    for (int k = 0; k <= 16; ++k) {
      const double x = -0.5 + 0.25 * k;
      poses.push_back(flat ? BladePose{0.01 * k, {x, -0.5, 1.9}, {x, 3.5, 1.9}}
                           : BladePose{0.01 * k, {x, 1.3, 1.95}, {x, 1.3, 3}});
    }
    for (const CutMode mode : {CutMode::kProgressive, CutMode::kDeferred}) {
      SCOPED_TRACE(::testing::Message()
                   << (flat ? "flat" : "tip under the top") << ", "
                   << (mode == CutMode::kProgressive ? "progressive" : "deferred"));
      LatticeCut cut;
      ASSERT_NO_FATAL_FAILURE(CutAlong(
          *mesh::MakeBoxLattice({.cells_x = 3, .cells_y = 3, .cells_z = 2}), poses, mode, &cut));
      EXPECT_GT(cut.statistics.cut_tets, 0u);
      EXPECT_GT(cut.fidelity.samples, 0u);
      // Flat, the box's top edges stay uncut along a rim: their vertices' normals are 45 degrees
      // from the blade's plane, so they snap, and the skin there is left on the surface.
      EXPECT_GE(cut.fidelity.coverage, flat ? 0.97 : 1.0);
      EXPECT_EQ(cut.fidelity.overcut_faces, 0u);
    }
  }
}

// A blade coming in through the box's top 35 degrees from it, its edge running along y at
// x = 0.616 there and its tip deep inside: the top's vertices at x = 1 lie 0.22 under the blade's
// plane, within the snap reach, but 0.38 from where it came in. Snapped, they moved the crack's rim
// to them, and 0.962 of the swept surface was covered; they stay off the crack, and all is.
TEST(CrackCutter, ABladeComingInObliquelyCutsAlongItsWayIn) {
  const double angle = 35 * M_PI / 180;
  const Eigen::Vector3d down(std::cos(angle), 0, -std::sin(angle));
  std::vector<BladePose> poses;
  for (int k = 0; k <= 16; ++k) {
    const Eigen::Vector3d way_in(0.616, -0.5 + 0.25 * k, 2);
    poses.push_back({0.01 * k, way_in + 2 * down, way_in - 0.5 * down});
  }
  for (const CutMode mode : {CutMode::kProgressive, CutMode::kDeferred}) {
    SCOPED_TRACE(mode == CutMode::kProgressive ? "progressive" : "deferred");
    LatticeCut cut;
    ASSERT_NO_FATAL_FAILURE(CutAlong(
        *mesh::MakeBoxLattice({.cells_x = 3, .cells_y = 3, .cells_z = 2}), poses, mode, &cut));
    EXPECT_GT(cut.fidelity.samples, 100u);
    EXPECT_EQ(cut.fidelity.coverage, 1);
    EXPECT_EQ(cut.fidelity.overcut_faces, 0u);
    EXPECT_EQ(cut.fidelity.unpaired_faces, 0u);
  }
}

}  // namespace
}  // namespace kerf::cut
