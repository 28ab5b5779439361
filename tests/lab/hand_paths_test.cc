#include "lab/hand_paths.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "mesh/box_lattice.h"
#include "mesh/mesh_quality.h"
#include "sim/blade_messages.h"

namespace kerf::lab {
namespace {

using cut::BladePose;

mesh::TetMesh Lattice() {
  return *mesh::MakeBoxLattice(
      {.cells_x = 6, .cells_y = 6, .cells_z = 4, .size = Eigen::Vector3d(0.06, 0.06, 0.04)});
}

cut::BladeLimits Limits(const mesh::TetMesh& m) {
  const double diagonal = mesh::MeasureBounds(m).diagonal();
  return {.max_length = 2 * diagonal, .max_step = 0.25 * diagonal, .max_speed = HUGE_VAL};
}

constexpr PathFamily kFamilies[] = {PathFamily::kHand, PathFamily::kThroughVertices,
                                    PathFamily::kAlongEdges, PathFamily::kInFacePlane};

TEST(HandPaths, EveryFamilyGivesValidPosesAndTheSameForTheSameSeed) {
  const mesh::TetMesh m = Lattice();
  for (const PathFamily family : kFamilies) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      const std::vector<BladePose> poses = MakeHandPath(m, family, seed);
      ASSERT_GT(poses.size(), 20u) << PathFamilyName(family);
      for (std::size_t i = 0; i < poses.size(); ++i) {
        ASSERT_TRUE(ValidatePose(poses[i], i ? &poses[i - 1] : nullptr, Limits(m)).ok())
            << PathFamilyName(family) << " seed " << seed << " pose " << i;
      }
      const std::vector<BladePose> again = MakeHandPath(m, family, seed);
      ASSERT_EQ(again.size(), poses.size());
      EXPECT_EQ(again.back().tip, poses.back().tip);
      EXPECT_NE(MakeHandPath(m, family, seed + 100).front().tip, poses.front().tip);
    }
  }
}

TEST(HandPaths, JsonReadsBackExactly) {
  const mesh::TetMesh m = Lattice();
  const std::vector<BladePose> poses = MakeHandPath(m, PathFamily::kHand, 4);
  const absl::StatusOr<std::vector<BladePose>> read =
      sim::ParseBladePathJson(FormatBladePathJson(poses), "made", Limits(m));
  ASSERT_TRUE(read.ok()) << read.status();
  ASSERT_EQ(read->size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    ASSERT_EQ((*read)[i].time, poses[i].time);
    ASSERT_EQ((*read)[i].tip, poses[i].tip);
    ASSERT_EQ((*read)[i].heel, poses[i].heel);
  }
}

// The tip's position along the pass's direction and across it, from the first pose.
struct Motion {
  std::vector<double> along, across;
};
Motion MotionOf(const std::vector<BladePose>& poses) {
  const Eigen::Vector3d d = (poses.back().tip - poses.front().tip).normalized();
  const Eigen::Vector3d side = Eigen::Vector3d::UnitZ().cross(d).normalized();
  Motion m;
  for (const BladePose& p : poses) {
    m.along.push_back((p.tip - poses.front().tip).dot(d));
    m.across.push_back((p.tip - poses.front().tip).dot(side));
  }
  return m;
}

TEST(HandPaths, AHandTremblesHesitatesAndReverses) {
  const mesh::TetMesh m = Lattice();
  const double edge = mesh::MeanEdgeLength(m);
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const std::vector<BladePose> poses = MakeHandPath(m, PathFamily::kHand, seed);
    EXPECT_DOUBLE_EQ(poses[1].time - poses[0].time, 1e-3);  // 1 kHz
    const Motion motion = MotionOf(poses);
    double widest = 0;
    for (const double a : motion.across) widest = std::max(widest, std::abs(a));
    EXPECT_GT(widest, 0.02 * edge) << seed;  // tremor ...
    EXPECT_LT(widest, 0.5 * edge) << seed;   // ... of a hand, not a swing
    // Going back: the tip's travel falls by over a tenth of an edge somewhere (back-offs and
    // the reversal), while tremor along the pass alone is at most 0.1 of an edge.
    double most = -HUGE_VAL, deepest_fall = 0;
    for (const double s : motion.along) {
      most = std::max(most, s);
      deepest_fall = std::max(deepest_fall, most - s);
    }
    EXPECT_GT(deepest_fall, 0.3 * edge) << seed;
    // Blade straight up, tip below the heel.
    EXPECT_LT(poses[0].tip.z(), poses[0].heel.z());
  }
}

TEST(HandPaths, DegenerateTipsPassThroughVerticesAndAlongEdges) {
  const mesh::TetMesh m = Lattice();
  for (const PathFamily family : {PathFamily::kThroughVertices, PathFamily::kAlongEdges}) {
    const std::vector<BladePose> poses = MakeHandPath(m, family, 2);
    std::vector<mesh::VertexId> visited;
    for (const BladePose& p : poses) {
      for (const mesh::VertexId v : m.vertices()) {
        if (m.rest_position(v) == p.tip) visited.push_back(v);
      }
    }
    EXPECT_GE(visited.size(), 3u) << PathFamilyName(family);
    if (family != PathFamily::kAlongEdges) continue;
    for (std::size_t i = 1; i < visited.size(); ++i) {
      EXPECT_FALSE(m.TetsAroundEdge(visited[i - 1], visited[i]).empty()) << i;
    }
  }
}

TEST(HandPaths, AFacePlaneBladeLiesInAFacesPlane) {
  const mesh::TetMesh m = Lattice();
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const std::vector<BladePose> poses = MakeHandPath(m, PathFamily::kInFacePlane, seed);
    // Every tip and heel in one plane, through three mesh vertices.
    const Eigen::Vector3d a = poses.front().tip, b = poses.front().heel, c = poses.back().tip;
    const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
    for (const BladePose& p : poses) {
      EXPECT_NEAR((p.tip - a).dot(normal), 0, 1e-12);
      EXPECT_NEAR((p.heel - a).dot(normal), 0, 1e-12);
    }
    int in_plane = 0;
    for (const mesh::VertexId v : m.vertices()) {
      in_plane += std::abs((m.rest_position(v) - a).dot(normal)) < 1e-12 ? 1 : 0;
    }
    EXPECT_GE(in_plane, 3) << seed;
  }
}

TEST(HandPaths, UnknownFamiliesAreNamed) {
  EXPECT_EQ(*ParsePathFamily("face-plane"), PathFamily::kInFacePlane);
  EXPECT_EQ(ParsePathFamily("wobble").status().message(),
            "unknown path family \"wobble\" (known: hand, vertices, edges, face-plane)");
}

}  // namespace
}  // namespace kerf::lab
