#include "cut/blade_crossings.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>

#include "mesh/box_lattice.h"
#include "mesh/mesh_quality.h"
#include "support/unit_tet.h"

namespace kerf::cut {
namespace {

using mesh::TetMesh;
using mesh::VertexId;

const auto kNoEdge = [](VertexId, VertexId) { return false; };
const auto kNoFace = [](const std::array<VertexId, 3>&) { return false; };

std::vector<mesh::TetVertices> All(const TetMesh& m) {
  std::vector<mesh::TetVertices> tets;
  for (const mesh::TetId t : m.tets()) tets.push_back(m.tet(t));
  return tets;
}

TEST(BladeCrossings, ASweepThroughATetCrossesTheEdgesItPasses) {
  TetMesh m = kerf::testing::UnitTet();
  BladeCrossings crossings = *BladeCrossings::Create(&m, 1);
  // The plane x = 0.25 swept from below the tet to above it: the three edges from corner 1.
  const BladePose from{0, {0.25, -1, -1}, {0.25, 2, -1}}, to{1, {0.25, -1, 2}, {0.25, 2, 2}};
  const Crossings found = crossings.Find(from, to, All(m), kNoEdge, kNoFace);
  ASSERT_EQ(found.edges.size(), 3u);
  for (const EdgeCrossing& e : found.edges) {
    EXPECT_TRUE(e.low == VertexId(1) || e.high == VertexId(1));
    // x = 0.25 is a quarter of the way from corner 0 to 1, three quarters from 1 to 2 or 3.
    EXPECT_NEAR(e.fraction, e.low == VertexId(0) ? 0.25 : 0.75, 1e-12);
  }
  EXPECT_TRUE(found.faces.empty());  // the tip stays below and above the tet
  // Skipping an edge (cut already) leaves it out.
  const Crossings skipped = crossings.Find(
      from, to, All(m), [](VertexId a, VertexId b) { return a == VertexId(0) && b == VertexId(1); },
      kNoFace);
  EXPECT_EQ(skipped.edges.size(), 2u);
}

// The tets near a step of the blade hold every crossing the step makes with the whole mesh:
// random steps of long oblique blades through a lattice, each found alike from NearSweep's tets
// and from all of them; and NearSweep lists far fewer tets than meet the step's box.
TEST(BladeCrossings, TheTetsNearASweepHoldEveryCrossingItMakes) {
  TetMesh m = *mesh::MakeBoxLattice(
      {.cells_x = 10, .cells_y = 10, .cells_z = 10, .size = {0.1, 0.1, 0.1}});  // 6,000 tets
  BladeCrossings crossings = *BladeCrossings::Create(&m, 0.01);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> near_low(-0.01, 0.03), step(-0.004, 0.004);
  const auto key = [](const EdgeCrossing& e) { return std::pair(e.low, e.high); };
  std::size_t near_total = 0, box_total = 0, edges_total = 0;
  for (int trial = 0; trial < 40; ++trial) {
    // Drawn one at a time: the order of a call's arguments differs between compilers.
    const auto draw = [&](auto& distribution) {
      Eigen::Vector3d v;
      for (int axis = 0; axis < 3; ++axis) v[axis] = distribution(random);
      return v;
    };
    const Eigen::Vector3d tip = draw(near_low);
    Eigen::Vector3d heel = Eigen::Vector3d::Constant(0.1) - draw(near_low);
    heel.z() = 0.1;
    const Eigen::Vector3d move = draw(step);
    const BladePose from{0, tip, heel}, to{0.001, tip + move, heel + 0.5 * move};
    std::vector<mesh::TetVertices> near;
    for (const mesh::TetId t : crossings.NearSweep(from, to, 0)) near.push_back(m.tet(t));
    const Crossings all = crossings.Find(from, to, All(m), kNoEdge, kNoFace);
    const Crossings found = crossings.Find(from, to, near, kNoEdge, kNoFace);
    std::vector<std::pair<VertexId, VertexId>> expected, got;
    for (const EdgeCrossing& e : all.edges) expected.push_back(key(e));
    for (const EdgeCrossing& e : found.edges) got.push_back(key(e));
    std::sort(expected.begin(), expected.end());
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, expected) << "trial " << trial;
    EXPECT_EQ(found.faces.size(), all.faces.size()) << "trial " << trial;
    near_total += near.size();
    edges_total += all.edges.size();
    const Eigen::Vector3d lo = from.tip.cwiseMin(from.heel).cwiseMin(to.tip).cwiseMin(to.heel);
    const Eigen::Vector3d hi = from.tip.cwiseMax(from.heel).cwiseMax(to.tip).cwiseMax(to.heel);
    for (const mesh::TetId t : m.tets()) {
      const mesh::Bounds box = mesh::MeasureTetBounds(m, t, /*current=*/true);
      box_total += (box.low.array() <= hi.array()).all() && (box.high.array() >= lo.array()).all();
    }
  }
  EXPECT_GT(edges_total, 200u);  // the steps do cross edges
  EXPECT_LT(near_total, box_total / 3);
}

TEST(BladeCrossings, TheTipGoingInCrossesAFace) {
  TetMesh m = kerf::testing::UnitTet();
  BladeCrossings crossings = *BladeCrossings::Create(&m, 1);
  // The tip goes up through the face z = 0 into the tet.
  const BladePose from{0, {0.2, 0.3, -0.5}, {0.2, 0.3, -1.5}},
      to{1, {0.2, 0.3, 0.2}, {0.2, 0.3, -0.8}};
  const Crossings found = crossings.Find(from, to, All(m), kNoEdge, kNoFace);
  ASSERT_EQ(found.faces.size(), 1u);
  EXPECT_EQ(found.faces[0].face, (std::array<VertexId, 3>{VertexId(0), VertexId(1), VertexId(2)}));
  EXPECT_NEAR(found.faces[0].barycentric[1], 0.2, 1e-12);
  EXPECT_NEAR(found.faces[0].barycentric[2], 0.3, 1e-12);
  EXPECT_TRUE(crossings.BladeMeets(m.tet(mesh::TetId(0)), to));
  EXPECT_FALSE(crossings.BladeMeets(m.tet(mesh::TetId(0)), from));
  // Withdrawn there, the blade crosses that face.
  const std::vector<FaceCrossing> at = crossings.FacesCrossedBy(to, All(m), kNoFace);
  ASSERT_EQ(at.size(), 1u);
  EXPECT_EQ(at[0].face, found.faces[0].face);
}

TEST(BladeCrossings, ATipAlongAFacesPlaneCrossesTheEdgesItPasses) {
  TetMesh m = kerf::testing::UnitTet();
  BladeCrossings crossings = *BladeCrossings::Create(&m, 1);
  // The blade stands in the plane y = 0 (face 0-1-3's) and its tip runs along z = 0.5 across
  // edge 0-3 at its middle; the blade's edge never crosses an edge there, its tip's path does.
  const BladePose from{0, {-0.5, 0, 0.5}, {-0.5, 0, 2}}, to{1, {0.25, 0, 0.5}, {0.25, 0, 2}};
  const Crossings found = crossings.Find(from, to, All(m), kNoEdge, kNoFace);
  const auto on_0_3 = std::find_if(
      found.edges.begin(), found.edges.end(),
      [](const EdgeCrossing& e) { return e.low == VertexId(0) && e.high == VertexId(3); });
  ASSERT_NE(on_0_3, found.edges.end());
  EXPECT_NEAR(on_0_3->fraction, 0.5, 1e-12);
}

TEST(BladeCrossings, TissueMovingAcrossAStillBladeIsCut) {
  TetMesh m = kerf::testing::UnitTet();
  BladeCrossings crossings = *BladeCrossings::Create(&m, 1);
  const BladePose still_a{0, {0.25, -1, -1}, {0.25, 2, -1}};
  const BladePose still_b{1, {0.25, -1, -1}, {0.25, 2, -1}};
  std::vector<VertexId> all = {VertexId(0), VertexId(1), VertexId(2), VertexId(3)};
  ASSERT_TRUE(crossings.Remember(all).ok());
  EXPECT_TRUE(crossings.Find(still_a, still_b, All(m), kNoEdge, kNoFace).edges.empty());
  // The tet moves down by 3 through the still blade: the three edges from corner 1 cross it.
  for (const VertexId v : all) {
    m.set_current_position(v, m.current_position(v) - Eigen::Vector3d(0, 0, 3));
  }
  ASSERT_TRUE(crossings.MeshDeformed().ok());
  EXPECT_EQ(crossings.Find(still_a, still_b, All(m), kNoEdge, kNoFace).edges.size(), 3u);
}

}  // namespace
}  // namespace kerf::cut
