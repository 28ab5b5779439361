#include "cut/blade_crossings.h"

#include <gtest/gtest.h>

#include <algorithm>

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
