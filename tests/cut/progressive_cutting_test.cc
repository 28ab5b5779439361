// Progressive cutting (the paper's section 4): the scripted paths that reach each of Table 1's
// eleven cases, with the properties of cutting.md checked after every pose, and the same paths
// cut deferred for comparison.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <set>

#include "absl/strings/str_cat.h"
#include "cut/cutter.h"
#include "cut/lag_meter.h"
#include "cut/progressive_case_paths.h"
#include "geometry/segment_distance.h"
#include "mesh/connected_components.h"
#include "mesh/cut_surface.h"
#include "mesh/face_tiling.h"
#include "mesh/mesh_validation.h"

namespace kerf::cut {
namespace {

using mesh::TetMesh;
using mesh::VertexId;

double RestVolume(const TetMesh& m) {
  double volume = 0;
  for (const mesh::TetId t : m.tets()) volume += mesh::RestVolume(m, t);
  return volume;
}

struct PathResult {
  CutStatistics statistics;
  double volume = 0;
  double crack_area = 0;
  std::size_t components = 0;
};

// Cuts the scripted lattice along `path` in `mode`, checking after every pose: valid (1),
// conforming with no face split differently on its two sides and the surface tiled once (2,
// 6), volume kept (3), the temporary points on the blade unless the pose was held (4), and
// at most 16 tets standing for
// a tet (7: the cone's largest count; the final cases keep tet_split's bounds).
PathResult CutChecked(const ScriptedPath& path, CutMode mode) {
  TetMesh m = ScriptedPathLattice();
  const TetMesh uncut = m;
  const double volume = RestVolume(m);
  Cutter cutter = *Cutter::Create(&m, 0.01, {}, mode);
  const auto source = [&](mesh::TetId t) { return cutter.SourceTet(t); };
  for (std::size_t i = 0; i < path.poses.size(); ++i) {
    SCOPED_TRACE(testing::Message() << path.name << " pose " << i);
    const BladePose& pose = path.poses[i];
    EXPECT_TRUE(cutter.ApplyPose(pose).ok());
    EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
    EXPECT_NEAR(RestVolume(m), volume, 1e-12 * volume);
    EXPECT_TRUE(mesh::CheckOriginalFacesTiled(uncut, m, source).ok())
        << mesh::CheckOriginalFacesTiled(uncut, m, source);
    for (const VertexId v : m.vertices()) {
      // A held pose keeps the previous pose's points.
      if (cutter.last_pose().held || !cutter.IsOnBladeNow(v)) continue;
      EXPECT_LT(geometry::DistanceToSegment(m.current_position(v), pose.tip, pose.heel), 1e-12);
    }
    EXPECT_LE(cutter.last_pose().temporary_tets, 16 * cutter.last_pose().open_tets);
    if (::testing::Test::HasFailure()) break;
  }
  cutter.Finish();
  EXPECT_EQ(cutter.waiting_tets(), 0u);
  EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
  EXPECT_NEAR(RestVolume(m), volume, 1e-12 * volume);
  EXPECT_TRUE(mesh::CheckOriginalFacesTiled(uncut, m, source).ok())
      << mesh::CheckOriginalFacesTiled(uncut, m, source);
  const CutStatistics& s = cutter.statistics();
  EXPECT_LE(s.new_tets, 10 * s.cut_tets);
  return {s, RestVolume(m), mesh::MeasureCrackArea(m), mesh::FindConnectedComponents(m).count};
}

TEST(ProgressiveCase, FollowsTableOne) {
  EXPECT_EQ(ProgressiveCase(0, 1, 1, true, false), 1);
  EXPECT_EQ(ProgressiveCase(0, 2, 2, false, false), 2);
  EXPECT_EQ(ProgressiveCase(1, 0, 2, false, false), 3);
  EXPECT_EQ(ProgressiveCase(1, 1, 1, true, false), 4);
  EXPECT_EQ(ProgressiveCase(1, 2, 2, false, false), 5);
  EXPECT_EQ(ProgressiveCase(2, 0, 2, false, true), 6);
  EXPECT_EQ(ProgressiveCase(2, 1, 1, true, true), 7);
  EXPECT_EQ(ProgressiveCase(2, 2, 2, false, true), 8);
  EXPECT_EQ(ProgressiveCase(2, 2, 2, false, false), 9);
  EXPECT_EQ(ProgressiveCase(3, 0, 2, false, false), 10);
  EXPECT_EQ(ProgressiveCase(3, 1, 1, true, false), 11);
  EXPECT_EQ(ProgressiveCase(0, 0, 2, false, false), 0);
  EXPECT_EQ(ProgressiveCase(4, 0, 2, false, false), 0);
}

// Each of the eleven cases is reached by the scripted path written for it, and every pose of
// every path keeps the properties.
TEST(ProgressiveCutting, EveryCaseIsReachedAndEveryPoseKeepsTheProperties) {
  std::set<int> reached;
  for (const ScriptedPath& path : ProgressiveCasePaths()) {
    const PathResult result = CutChecked(path, CutMode::kProgressive);
    for (const int k : path.expected_cases) {
      EXPECT_GT(result.statistics.poses_by_case[k], 0u) << path.name << " case " << k;
      reached.insert(k);
    }
    EXPECT_GT(result.statistics.rebuilt, 0u) << path.name;
    EXPECT_GT(result.statistics.moved, 0u) << path.name;
  }
  EXPECT_EQ(reached.size(), static_cast<std::size_t>(kProgressiveCases));
}

// The paths that leave the bar end, cut either way, in meshes of the same volume and crack
// area, and with the same pieces. Exactly so for a blade that goes straight through; a blade
// trembling back over tets it has left recuts them when cut progressively (they are final
// already), where the deferred cutter still holds them whole: the areas then differ by 2e-5.
TEST(ProgressiveCutting, EndsLikeDeferredCuttingWhenTheBladeLeaves) {
  int compared = 0;
  for (const ScriptedPath& path : ProgressiveCasePaths()) {
    if (path.name != "through" && path.name != "tilting-tremble") continue;
    const PathResult progressive = CutChecked(path, CutMode::kProgressive);
    const PathResult deferred = CutChecked(path, CutMode::kDeferred);
    EXPECT_NEAR(progressive.volume, deferred.volume, 1e-12 * deferred.volume) << path.name;
    EXPECT_GT(deferred.crack_area, 0) << path.name;
    const double tolerance = path.name == "through" ? 1e-9 : 1e-4;
    EXPECT_NEAR(progressive.crack_area, deferred.crack_area, tolerance * deferred.crack_area)
        << path.name;
    EXPECT_EQ(progressive.components, deferred.components) << path.name;
    EXPECT_EQ(progressive.components, 2u) << path.name;
    ++compared;
  }
  EXPECT_EQ(compared, 2);
}

// The blade stops, hesitates and turns back inside tets, and is withdrawn there: the crack it
// made stays, in both modes (deferred cutting ends it on the faces where the blade left it).
TEST(ProgressiveCutting, ACrackWithdrawnInsideTetsStays) {
  for (const ScriptedPath& path : ProgressiveCasePaths()) {
    if (path.name != "stop-turn-withdraw") continue;
    const PathResult progressive = CutChecked(path, CutMode::kProgressive);
    EXPECT_GT(progressive.crack_area, 0.5 * 0.007 * 0.0073);  // 12.5 mm travelled, 7.3 mm deep
    EXPECT_GT(progressive.statistics.frozen_tets + progressive.statistics.cut_tets, 0u);
    const PathResult deferred = CutChecked(path, CutMode::kDeferred);
    std::printf("withdrawn inside: crack %.1f mm2 progressive, %.1f deferred (%zu hits dropped)\n",
                1e6 * progressive.crack_area, 1e6 * deferred.crack_area,
                deferred.statistics.dropped_hits);
    EXPECT_GT(deferred.crack_area, 0.5 * 0.007 * 0.0073);
    EXPECT_EQ(deferred.statistics.dropped_hits, 0u);
    return;
  }
  FAIL() << "no stop-turn-withdraw path";
}

// When only the blade moved inside its tets, their temporary points move in place: no vertex or
// tet is made, so a long cut does not grow the mesh's arrays pose by pose.
TEST(ProgressiveCutting, PointsThatOnlyMoveKeepTheirVerticesAndTets) {
  const ScriptedPath path = ProgressiveCasePaths().front();
  ASSERT_EQ(path.name, "through");
  TetMesh m = ScriptedPathLattice();
  Cutter cutter = *Cutter::Create(&m, 0.01, {}, CutMode::kProgressive);
  std::vector<BladePose> poses = {path.poses.front()};  // ten poses per step of the path
  for (std::size_t i = 1; i < path.poses.size(); ++i) {
    const BladePose &a = path.poses[i - 1], &b = path.poses[i];
    for (int k = 1; k <= 10; ++k) {
      const double s = k / 10.0;
      poses.push_back({a.time + s * (b.time - a.time), a.tip + s * (b.tip - a.tip),
                       a.heel + s * (b.heel - a.heel)});
    }
  }
  std::size_t moving_poses = 0;
  for (const BladePose& pose : poses) {
    const CutStatistics before = cutter.statistics();
    const std::uint32_t vertices = m.vertex_index_bound(), tets = m.tet_index_bound();
    const std::vector<VertexId> live(m.vertices().begin(), m.vertices().end());
    ASSERT_TRUE(cutter.ApplyPose(pose).ok());
    const CutStatistics& after = cutter.statistics();
    if (after.moved == before.moved || after.rebuilt != before.rebuilt ||
        after.cut_tets != before.cut_tets || after.held_poses != before.held_poses) {
      continue;
    }
    ++moving_poses;
    EXPECT_EQ(m.vertex_index_bound(), vertices);
    EXPECT_EQ(m.tet_index_bound(), tets);
    EXPECT_EQ(std::vector<VertexId>(m.vertices().begin(), m.vertices().end()), live);
  }
  EXPECT_GT(moving_poses, 10u);
}

// The opening keeps up with the blade: on the straight through-cut the lag is zero at every
// pose progressively, and grows with the cut when deferred.
// A blade that stops exactly in the planes of lattice faces, crossing lattice edges there,
// through the whole bar and with its tip inside: the crack's front runs through those edges
// (closed cuts), so no pose is held and every property holds after every pose.
TEST(ProgressiveCutting, ABladeInTheFacesPlanesThroughEdgesHoldsNoPose) {
  for (const double tip_z : {-0.005, 0.0137}) {
    ScriptedPath path;
    path.name = absl::StrCat("in planes, tip at z ", tip_z);
    for (int i = 0; i <= 24; ++i) {
      const double x = -0.005 + 0.0025 * i;  // every fourth pose in the plane x = 0, 1, .. cm
      path.poses.push_back({.time = 0.01 * i, .tip = {x, 0.013, tip_z}, .heel = {x, 0.013, 0.025}});
    }
    const PathResult result = CutChecked(path, CutMode::kProgressive);
    EXPECT_EQ(result.statistics.held_poses, 0u) << path.name;
    EXPECT_EQ(result.statistics.uncovered_temporary_plans, 0u) << path.name;
    EXPECT_EQ(result.statistics.dropped_hits, 0u) << path.name;
    EXPECT_GT(result.statistics.cut_tets, 0u) << path.name;
  }
}

TEST(ProgressiveCutting, TheOpeningKeepsUpWithTheBlade) {
  for (const CutMode mode : {CutMode::kProgressive, CutMode::kDeferred}) {
    const ScriptedPath path = ProgressiveCasePaths().front();
    ASSERT_EQ(path.name, "through");
    TetMesh m = ScriptedPathLattice();
    LagMeter meter(m);
    Cutter cutter = *Cutter::Create(&m, 0.01, {}, mode);
    int most_steps = 0;
    double largest = 0;
    for (const BladePose& pose : path.poses) {
      ASSERT_TRUE(cutter.ApplyPose(pose).ok());
      const PoseLag lag = meter.Measure(pose, mesh::MeasureCrackArea(m));
      most_steps = std::max(most_steps, lag.lag_steps);
      largest = std::max(largest, lag.lag_area);
    }
    if (mode == CutMode::kProgressive) {
      EXPECT_EQ(most_steps, 0);
    } else {
      EXPECT_GE(most_steps, 20);              // the whole cut waits for the blade to leave
      EXPECT_GT(largest, 0.5 * 0.02 * 0.02);  // over half the bar's cross-section
    }
  }
}

}  // namespace
}  // namespace kerf::cut
