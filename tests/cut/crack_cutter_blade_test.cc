// What the crack cutter tells the simulation about the blade it is cutting with: the tets that
// hold the blade, the softening of thin pieces on it, and the paper's Table 1 cases it meets.
#include <gtest/gtest.h>

#include <set>

#include "cut/crack_cutter.h"
#include "geometry/tet_measures.h"
#include "lab/crack_fidelity.h"
#include "lab/hand_paths.h"
#include "lab/progressive_case_paths.h"
#include "mesh/box_lattice.h"
#include "mesh/face_tiling.h"
#include "mesh/io/mesh_file.h"
#include "mesh/mesh_quality.h"
#include "mesh/mesh_validation.h"
#include "support/shared_meshes.h"
#include "support/unit_tet.h"

namespace kerf::cut {
namespace {

using mesh::TetMesh;

constexpr BladeLimits kLoose = {.max_length = 10, .max_step = 10, .max_speed = 100};

double RestVolumeOf(const TetMesh& m, const mesh::TetVertices& v) {
  return std::abs(geometry::SignedVolume(m.rest_position(v[0]), m.rest_position(v[1]),
                                         m.rest_position(v[2]), m.rest_position(v[3])));
}

// A blade entering through the face z = 0, its tip inside: the tet is held as the pieces it
// stands in now, which fill it; a blade beside the tet holds nothing.
TEST(CrackCutterBlade, TheTetsHoldingTheBladeAreThePiecesOfTheTetItOpens) {
  TetMesh m = kerf::testing::UnitTet();
  CrackCutter cutter = *CrackCutter::Create(&m, 1, kLoose);
  ASSERT_TRUE(cutter.ApplyPose({0, {0.2, 0.2, -1}, {0.2, 0.2, -2}}).ok());
  EXPECT_TRUE(cutter.TetsHoldingBlade({0, {0.2, 0.2, -1}, {0.2, 0.2, -2}}).empty());
  const BladePose in = {0.1, {0.2, 0.2, 0.3}, {0.2, 0.2, -0.7}};
  ASSERT_TRUE(cutter.ApplyPose(in).ok());
  ASSERT_GT(m.tet_count(), 1u);  // opened at once
  const std::vector<mesh::TetVertices> holding = cutter.TetsHoldingBlade(in);
  EXPECT_EQ(holding.size(), m.tet_count());
  double volume = 0;
  for (const mesh::TetVertices& t : holding) volume += RestVolumeOf(m, t);
  EXPECT_NEAR(volume, 1.0 / 6, 1e-15);
  EXPECT_TRUE(cutter.TetsHoldingBlade({0.1, {3, 3, 3}, {3, 3, 2}}).empty());
}

// A blade through the face z = 0 a five-hundredth of an edge from its edge y = 0 makes pieces
// far thinner than the tet: they are softened while the blade holds them, not once it has gone;
// with no guard nothing is.
TEST(CrackCutterBlade, ThinPiecesOnTheBladeAreSoftenedWhileItIsThere) {
  for (const double guard : {kDefaultMinTemporaryHeight, 0.0}) {
    TetMesh m = kerf::testing::UnitTet();
    CrackCutter cutter = *CrackCutter::Create(&m, 1, kLoose, {.min_temporary_height = guard});
    ASSERT_TRUE(cutter.ApplyPose({0, {0.3, 0.002, -1}, {0.3, 0.002, -2}}).ok());
    ASSERT_TRUE(cutter.ApplyPose({0.1, {0.3, 0.002, 0.3}, {0.3, 0.002, -0.7}}).ok());
    double softest = 1;
    for (const mesh::TetId t : m.tets()) {
      const double scale = cutter.StiffnessScale(t);
      EXPECT_GT(scale, 0);
      EXPECT_LE(scale, 1);
      softest = std::min(softest, scale);
    }
    if (guard > 0) {
      EXPECT_LT(softest, 0.5);
    } else {
      EXPECT_EQ(softest, 1);
    }
    cutter.Finish();
    for (const mesh::TetId t : m.tets()) EXPECT_EQ(cutter.StiffnessScale(t), 1);
  }
}

// A blade lying in the plane of the tissue's surface (the face z = 0 of the unit tet), swept
// across that face through two of its edges, slides along the surface: it cuts nothing, in
// either mode. The same blade in the plane z = 0.4 cuts the tet.
TEST(CrackCutterBlade, ABladeSlidingAlongTheSurfaceCutsNothing) {
  for (const CutMode mode : {CutMode::kProgressive, CutMode::kDeferred}) {
    for (const double z : {0.0, 0.4}) {
      TetMesh m = kerf::testing::UnitTet();
      CrackCutter cutter = *CrackCutter::Create(&m, 1, kLoose, {.mode = mode});
      for (int k = 0; k <= 20; ++k) {
        const double x = -0.5 + 0.1 * k;
        ASSERT_TRUE(cutter.ApplyPose({0.01 * k, {x, -0.5, z}, {x, 1.5, z}}).ok());
        if (z == 0) {
          EXPECT_EQ(m.tet_count(), 1u) << "pose " << k;
        }
      }
      cutter.Finish();
      EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
      if (z == 0) {
        EXPECT_EQ(m.tet_count(), 1u);
        EXPECT_EQ(cutter.statistics().cut_tets, 0u);
      } else {
        EXPECT_EQ(cutter.statistics().cut_tets, 1u);
      }
    }
  }
}

// A blade entering the unit tet through its face x = 0 and withdrawn with its tip inside: the
// cone the tet splits into for good has its apex on the blade where it was withdrawn (as while it
// was in the tet), so the crack ends where the blade did rather than where the cone's angles
// are best.
TEST(CrackCutterBlade, TheCrackEndsWhereTheBladeIsWithdrawn) {
  for (const CutMode mode : {CutMode::kProgressive, CutMode::kDeferred}) {
    SCOPED_TRACE(mode == CutMode::kProgressive ? "progressive" : "deferred");
    TetMesh m = kerf::testing::UnitTet();
    const std::size_t corners = m.vertex_count();
    CrackCutter cutter = *CrackCutter::Create(&m, 1, kLoose, {.mode = mode});
    BladePose last;
    for (int k = 0; k <= 10; ++k) {
      const double x = -0.2 + 0.05 * k;
      last = {0.01 * k, {x, 0.25, 0.15}, {x, 0.25, 2}};
      ASSERT_TRUE(cutter.ApplyPose(last).ok());
    }
    cutter.Finish();
    ASSERT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
    std::size_t inner = 0;
    for (const mesh::VertexId v : m.vertices()) {
      const Eigen::Vector3d& p = m.rest_position(v);
      if (mesh::Index(v) < corners || p.minCoeff() < 1e-9 || p.sum() > 1 - 1e-9) continue;
      ++inner;  // a point the cut made strictly inside the tet: on the blade
      EXPECT_NEAR(p.x(), last.tip.x(), 1e-12);
      EXPECT_NEAR(p.y(), last.tip.y(), 1e-12);
    }
    EXPECT_GT(inner, 0u);
  }
}

// Hand paths through the livers withdrawn before their end, where the blade crossed a face beside
// an edge the crack had crossed elsewhere, the face's only point (taken at that edge, the crossing
// was dropped, and the crack the face had up to the blade with it: 0.930 and 0.984 of the swept
// surface below the tissue's surface covered after the withdrawal on liver.msh, 0.999 on
// liver2.msh, each 1 at the last pose), or with the tip inside a tet whose points alone fit a
// split that misses the tip (liver.msh seed 6 after pose 582, 0.920, and liver2.msh seed 8 after
// pose 1261, 0.987: that tet now splits as the cone from the tip, as while the blade was there):
// what the crack covered at the last pose it covers after.
TEST(CrackCutterBlade, AHandWithdrawnMidPathKeepsTheCrackItHad) {
  struct Withdrawal {
    const char* mesh;
    std::uint64_t seed;
    std::size_t last_pose;
  };
  for (const Withdrawal& w : {Withdrawal{"liver.msh", 4, 485}, Withdrawal{"liver.msh", 3, 776},
                              Withdrawal{"liver2.msh", 10, 776}, Withdrawal{"liver.msh", 6, 582},
                              Withdrawal{"liver2.msh", 8, 1261}}) {
    SCOPED_TRACE(::testing::Message()
                 << w.mesh << " hand seed " << w.seed << " to pose " << w.last_pose);
    const std::string path = kerf::testing::SharedMeshPath(w.mesh);
    if (path.empty()) GTEST_SKIP() << "no ../shared/meshes";
    const TetMesh tissue = *mesh::ReadMeshFile(path);
    const double diagonal = mesh::MeasureBounds(tissue).diagonal();
    const std::vector<BladePose> poses = lab::MakeHandPath(tissue, lab::PathFamily::kHand, w.seed);
    ASSERT_GT(poses.size(), w.last_pose + 1);  // withdrawn before the path's end
    TetMesh m = tissue;
    CrackCutter cutter = *CrackCutter::Create(
        &m, mesh::MeanEdgeLength(m),
        {.max_length = 2 * diagonal, .max_step = 0.25 * diagonal, .max_speed = 1e9});
    lab::FidelityMeter meter(tissue);
    for (std::size_t i = 0; i <= w.last_pose; ++i) {
      ASSERT_TRUE(cutter.ApplyPose(poses[i]).ok());
      if (i > 0) meter.AddStep(poses[i - 1], poses[i]);
    }
    const lab::Fidelity at_last_pose = meter.Measure(meter.FindCrack(m));
    cutter.Finish();
    ASSERT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
    const lab::Fidelity withdrawn = meter.Measure(meter.FindCrack(m));
    EXPECT_EQ(at_last_pose.coverage_below_surface, 1);
    EXPECT_EQ(withdrawn.coverage_below_surface, 1);
    EXPECT_EQ(withdrawn.overcut_faces, 0u);
  }
}

// Progressive: a blade through the whole depth of a bar goes into it, turns back inside a tet
// and comes out the way it went in: the crack reaches where it turned (without the farthest
// crossings of the faces it crossed kept as their points, the crack ended at the last edges it
// crossed: 0.92 of the sweep covered).
TEST(CrackCutterBlade, TheCrackReachesWhereTheBladeTurnedBack) {
  {
    const TetMesh bar = *mesh::MakeBoxLattice({.cells_x = 4, .cells_y = 4, .cells_z = 2});
    TetMesh m = bar;
    CrackCutter cutter = *CrackCutter::Create(&m, 1, kLoose);
    lab::FidelityMeter meter(bar);
    std::vector<BladePose> poses;
    for (int i = 0; i <= 92; ++i) {
      const double y = 1.8 - std::abs(2.3 - 0.05 * i);  // in from y = -0.5 to 1.8, and out
      poses.push_back({0.01 * i, {2.3, y, -0.5}, {2.3, y, 2.5}});
      ASSERT_TRUE(cutter.ApplyPose(poses.back()).ok());
      if (i > 0) meter.AddStep(poses[i - 1], poses[i]);
    }
    cutter.Finish();
    ASSERT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
    EXPECT_GE(meter.Measure(meter.FindCrack(m)).coverage, 0.99);
  }
}

// Progressive, in the unit tet: the blade, standing along +z, comes down through the tet's
// slanted face (x + y + z = 1) at `entry`, its tip going `depth` under it, then moves `sideways`
// in small steps without crossing an edge of the tet (every crossing a quarter of a face or more
// from its edges, so none snaps). After each sideways pose the crack reaches the blade: the
// step's own swept surface is covered (point-wise lag 0). Returns the least step coverage of the
// sideways poses.
double LeastCoverageMovingSideways(const Eigen::Vector3d& entry, double depth,
                                   const Eigen::Vector3d& sideways) {
  const TetMesh tet = kerf::testing::UnitTet();
  TetMesh m = tet;
  CrackCutter cutter = *CrackCutter::Create(&m, 1, kLoose);
  lab::FidelityMeter meter(tet);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  std::vector<BladePose> poses;
  for (int i = 0; i <= 10; ++i) {  // the plunge, along the blade: it sweeps nothing
    const Eigen::Vector3d tip = entry + (0.2 - (0.2 + depth) * i / 10) * up;
    poses.push_back({0.01 * i, tip, tip + 1.5 * up});
  }
  const int plunge = static_cast<int>(poses.size());
  for (int i = 1; i <= 20; ++i) {
    const Eigen::Vector3d tip = poses[plunge - 1].tip + sideways * i / 20;
    poses.push_back({0.01 * (plunge + i), tip, tip + 1.5 * up});
  }
  double least = 1;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_TRUE(cutter.ApplyPose(poses[i]).ok());
    if (i == 0) continue;
    const std::size_t step = meter.AddStep(poses[i - 1], poses[i]);
    EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << i << ": " << mesh::ValidateMesh(m);
    if (static_cast<int>(i) < plunge) continue;
    EXPECT_GT(meter.StepSamples(step), 0u) << i;
    least = std::min(least, meter.StepCoverage(meter.FindCrackNearStep(m, step), step));
  }
  cutter.Finish();
  EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
  return least;
}

// Table 1's first case: the tip came in by a face and stays inside; the blade moves on, crossing
// that face beside where the tip's path did. The crack runs from the tip's crossing of the face
// to the blade's (without the blade's point beside the face's own, the tet had no crack).
TEST(CrackCutterBlade, TheCrackReachesTheBladeInATetItsTipCameInBy) {
  EXPECT_EQ(LeastCoverageMovingSideways({0.3, 0.3, 0.4}, 0.15, {0.05, -0.03, 0}), 1);
}

// Table 1's second case: the tip's path went through two faces (the blade plunged through the
// tet, out by its face z = 0) and the blade moves on, crossing both beside those points.
TEST(CrackCutterBlade, TheCrackReachesTheBladeInATetItPlungedThrough) {
  EXPECT_EQ(LeastCoverageMovingSideways({0.3, 0.3, 0.4}, 0.5, {0.05, -0.03, 0}), 1);
}

// A tip trembling inside a tet of a lattice, the blade slanted through the tet above it (as in
// cutter_benchmark's ProgressivePoseInsideKTets/1): the cone from the tip stands (the same
// pieces at every pose) while its apex moves with the tip, and the points opening its crack
// faces (every corner of them on the crack's edge) move with those faces' middles; the mesh stays
// valid at every pose.
TEST(CrackCutterBlade, PiecesOpenedAtTheTipStandWhileTheTipTrembles) {
  const TetMesh lattice =
      *mesh::MakeBoxLattice({.cells_x = 2, .cells_y = 2, .cells_z = 8, .size = {0.02, 0.02, 0.08}});
  TetMesh m = lattice;
  CrackCutter cutter = *CrackCutter::Create(&m, 0.01, kLoose);
  const auto blade_at = [](int k, double y) {
    const Eigen::Vector3d tip(0.0063, y, 0.078);
    return BladePose{0.01 * k, tip, tip + 0.012 * Eigen::Vector3d(0.0011 / 0.09, 0, 1)};
  };
  int k = 0;
  for (double y = -0.005; y < 0.0047; y += 0.001)
    ASSERT_TRUE(cutter.ApplyPose(blade_at(k++, y)).ok());
  std::set<mesh::TetId> pieces;
  for (int i = 0; i < 10; ++i, ++k) {
    const BladePose pose = blade_at(k, 0.0047 + 0.0001 * (k % 2));
    ASSERT_TRUE(cutter.ApplyPose(pose).ok());
    ASSERT_TRUE(mesh::FindMeshDefects(m).empty()) << i << ": " << mesh::ValidateMesh(m);
    const std::set<mesh::TetId> now(m.tets().begin(), m.tets().end());
    if (i == 0) pieces = now;
    EXPECT_EQ(now, pieces) << "pose " << i;
    // The tissue's tet holding the tip, and the points the cut made strictly inside it: the
    // apex, at the tip, and the points opening crack faces through it, each the middle of the
    // apex and two other vertices.
    std::optional<mesh::TetId> holding;
    for (const mesh::TetId t : lattice.tets()) {
      const mesh::TetVertices& c = lattice.tet(t);
      if (geometry::ContainsPoint(lattice.rest_position(c[0]), lattice.rest_position(c[1]),
                                  lattice.rest_position(c[2]), lattice.rest_position(c[3]),
                                  pose.tip)) {
        holding = t;
      }
    }
    ASSERT_TRUE(holding.has_value());
    const mesh::TetVertices& c = lattice.tet(*holding);
    const auto at = [&](int j) { return lattice.rest_position(c[j]); };
    std::vector<mesh::VertexId> vertices(m.vertices().begin(), m.vertices().end());
    std::vector<Eigen::Vector3d> openings;
    bool apex = false;
    for (const mesh::VertexId v : vertices) {
      const Eigen::Vector3d& x = m.rest_position(v);
      if (geometry::BarycentricWeights(at(0), at(1), at(2), at(3), x).minCoeff() <= 1e-9) continue;
      if ((x - pose.tip).norm() < 1e-15) {
        apex = true;
      } else {
        openings.push_back(x);
      }
    }
    EXPECT_TRUE(apex) << "pose " << i;
    EXPECT_FALSE(openings.empty()) << "pose " << i;
    for (const Eigen::Vector3d& o : openings) {
      bool middle = false;
      for (const mesh::VertexId p : vertices) {
        for (const mesh::VertexId q : vertices) {
          const Eigen::Vector3d x = (pose.tip + m.rest_position(p) + m.rest_position(q)) / 3;
          middle = middle || (x - o).norm() < 1e-15;
        }
      }
      EXPECT_TRUE(middle) << "pose " << i << ": an opening at " << o.transpose();
    }
  }
  cutter.Finish();
  EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
}

// Hand paths through liver2.msh whose blade trembled and hesitated with its tip in tets it had
// come into by a face or plunged through (seeds 6, 8 and 10: 21, 13 and 25 poses on end whose own
// step was not all cut at once, below the surface, where the crack lay in the face the blade came
// in by, had no face in the tet, or ended on a chord short of the tip): the crack reaches the
// blade after every pose.
TEST(CrackCutterBlade, TheCrackKeepsUpWithAHandTremblingInsideTheLiver) {
  const std::string path = kerf::testing::SharedMeshPath("liver2.msh");
  if (path.empty()) GTEST_SKIP() << "no ../shared/meshes";
  const TetMesh liver = *mesh::ReadMeshFile(path);
  const double diagonal = mesh::MeasureBounds(liver).diagonal();
  for (const std::uint64_t seed : {6, 8, 10}) {
    SCOPED_TRACE(::testing::Message() << "hand seed " << seed);
    TetMesh m = liver;
    const std::vector<BladePose> poses = lab::MakeHandPath(liver, lab::PathFamily::kHand, seed);
    CrackCutter cutter = *CrackCutter::Create(
        &m, mesh::MeanEdgeLength(m),
        {.max_length = 2 * diagonal, .max_step = 0.25 * diagonal, .max_speed = 1e9});
    lab::FidelityMeter meter(liver);
    std::size_t lagging = 0, swept = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
      ASSERT_TRUE(cutter.ApplyPose(poses[i]).ok());
      if (i == 0) continue;
      const std::size_t step = meter.AddStep(poses[i - 1], poses[i]);
      swept += meter.StepSamples(step) > 0;
      lagging += meter.StepCoverageBelowSurface(meter.FindCrackNearStep(m, step), step) < 1;
    }
    cutter.Finish();
    EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
    EXPECT_GT(swept, 500u);
    EXPECT_EQ(lagging, 0u);
  }
}

// The scripted paths reach every case of the paper's Table 1, each pose valid and conforming
// (cut with the least snapping: the paths were found for crossings taken where they are).
TEST(CrackCutterBlade, EveryTableCaseIsReached) {
  std::set<int> reached;
  for (const lab::ScriptedPath& path : lab::ProgressiveCasePaths()) {
    const TetMesh lattice = lab::ScriptedPathLattice();
    TetMesh m = lattice;
    CrackCutter cutter = *CrackCutter::Create(&m, 0.01, {}, {.snap_fraction = 0});
    for (std::size_t i = 0; i < path.poses.size(); ++i) {
      ASSERT_TRUE(cutter.ApplyPose(path.poses[i]).ok()) << path.name << " pose " << i;
      ASSERT_TRUE(mesh::FindMeshDefects(m).empty())
          << path.name << " pose " << i << ": " << mesh::ValidateMesh(m);
      const absl::Status tiled = mesh::CheckOriginalFacesTiled(
          lattice, m, [&](mesh::TetId t) { return cutter.SourceTet(t); },
          [&](mesh::VertexId v) { return cutter.PartedFrom(v); });
      ASSERT_TRUE(tiled.ok()) << path.name << " pose " << i << ": " << tiled;
    }
    cutter.Finish();
    for (const int k : path.expected_cases) {
      EXPECT_GT(cutter.statistics().poses_by_case[k], 0u) << path.name << " case " << k;
      reached.insert(k);
    }
  }
  EXPECT_EQ(reached.size(), static_cast<std::size_t>(kProgressiveCases));
}

}  // namespace
}  // namespace kerf::cut
