#include "cut/face_split.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <map>
#include <random>

namespace kerf::cut {
namespace {

using mesh::VertexId;

// Corners 0, 1, 2; edge points 10, 11, 12 (on edges 0, 1, 2); inside point 20.
const VertexId kA{0}, kB{1}, kC{2};
constexpr VertexId E(int k) { return VertexId(10 + k); }
const VertexId kInside{20};

FacePoints Points(std::array<bool, 3> edges, bool inside = false,
                  std::array<bool, 3> corners_on_crack = {false, false, false}) {
  FacePoints p{{kA, kB, kC}, {}, std::nullopt, corners_on_crack, {}};
  for (int k = 0; k < 3; ++k) {
    if (edges[k]) p.on_edge[k] = E(k);
  }
  if (inside) p.inside = kInside;
  return p;
}

// Positions: a right triangle, edge points in the middle of their edges, the inside point at
// the centroid.
Eigen::Vector2d At(VertexId v) {
  static const std::map<int, Eigen::Vector2d> positions = {{0, {0, 0}},
                                                           {1, {1, 0}},
                                                           {2, {0, 1}},
                                                           {10, {0.5, 0}},
                                                           {11, {0.5, 0.5}},
                                                           {12, {0, 0.5}},
                                                           {20, {1.0 / 3, 1.0 / 3}},
                                                           {21, {0.3, 0.6}}};
  return positions.at(static_cast<int>(v));
}

double Area(const std::array<VertexId, 3>& t) {
  const Eigen::Vector2d u = At(t[1]) - At(t[0]), w = At(t[2]) - At(t[0]);
  return 0.5 * (u.x() * w.y() - u.y() * w.x());
}

TEST(FaceSplit, EveryPatternTilesTheFaceWithTrianglesOfOneOrientation) {
  for (int mask = 0; mask < 16; ++mask) {
    const FacePoints p = Points({(mask & 1) != 0, (mask & 2) != 0, (mask & 4) != 0}, mask & 8);
    if (NeedsHub(p)) {
      EXPECT_EQ(mask, 7);
      continue;
    }
    const FaceSplit split = SplitFace(p);
    double area = 0;
    for (const auto& t : split.triangles) {
      EXPECT_GT(Area(t), 1e-12) << "pattern " << mask;  // positive: the face's orientation
      area += Area(t);
    }
    EXPECT_NEAR(area, 0.5, 1e-15) << "pattern " << mask;
  }
}

// The blade crossing a face elsewhere than its point for good (the tip's path's): the fan's
// triangle holding it splits in three, the trace runs from the face's point to the blade's, and
// no triangle at the blade's point lies on the crack (the crack runs through the tet from it).
TEST(FaceSplit, APointBesideTheInsideOneSplitsItsFanTriangleAndIsTracedTo) {
  const VertexId beside{21};  // (0.3, 0.6): in the fan triangle from the inside point to c
  for (const bool edge_cut : {false, true}) {
    FacePoints p = Points({false, edge_cut, false}, true, {true, false, false});
    p.beside = beside;
    p.beside_between =
        edge_cut ? std::array<VertexId, 2>{kC, E(1)} : std::array<VertexId, 2>{kB, kC};
    const FaceSplit split = SplitFace(p);
    ASSERT_EQ(split.triangles.size(), edge_cut ? 6u : 5u);
    double area = 0;
    for (const auto& t : split.triangles) {
      EXPECT_GT(Area(t), 1e-12);
      area += Area(t);
    }
    EXPECT_NEAR(area, 0.5, 1e-15);
    EXPECT_NE(
        std::find(split.trace.begin(), split.trace.end(), std::array<VertexId, 2>{kInside, beside}),
        split.trace.end());
    for (const auto& t : split.on_crack) {
      EXPECT_EQ(std::count(t.begin(), t.end(), beside), 0);
    }
    const std::vector<VertexId> on_crack = PointsOnCrack(p);
    EXPECT_EQ(std::count(on_crack.begin(), on_crack.end(), beside), 0);
  }
}

TEST(FaceSplit, TwoEdgePointsCutOffTheirCornerAndSplitTheRestThroughTheSmallestId) {
  // Edges 0 (a-b) and 1 (b-c) cut: corner b comes off; the quad (e1, c, a, e0) is split through
  // a, its corner of smallest id.
  const FaceSplit split = SplitFace(Points({true, true, false}));
  ASSERT_EQ(split.triangles.size(), 3u);
  EXPECT_EQ(split.triangles[0], (std::array<VertexId, 3>{kB, E(1), E(0)}));
  bool diagonal_through_a = false;
  for (const auto& t : split.triangles) {
    diagonal_through_a |=
        std::count(t.begin(), t.end(), kA) && std::count(t.begin(), t.end(), E(1));
  }
  EXPECT_TRUE(diagonal_through_a);
  EXPECT_EQ(split.trace, (std::vector<std::array<VertexId, 2>>{{E(0), E(1)}}));
  EXPECT_TRUE(split.on_crack.empty());
}

TEST(FaceSplit, OneEdgePointSplitsFromTheOppositeCornerAndTracesToCornersOnTheCrack) {
  const FaceSplit alone = SplitFace(Points({false, true, false}));
  EXPECT_EQ(alone.triangles.size(), 2u);
  EXPECT_TRUE(alone.trace.empty());
  const FaceSplit through_a = SplitFace(Points({false, true, false}, false, {true, false, false}));
  EXPECT_EQ(through_a.triangles, alone.triangles);  // corners never change the triangles
  EXPECT_EQ(through_a.trace, (std::vector<std::array<VertexId, 2>>{{kA, E(1)}}));
}

TEST(FaceSplit, AnInsidePointFansAndTracesToEachEdgePoint) {
  const FaceSplit split = SplitFace(Points({true, false, true}, true, {false, true, false}));
  EXPECT_EQ(split.triangles.size(), 5u);
  EXPECT_EQ(split.trace.size(), 2u);  // to e0 and e2; corner b is not, the face has points
  const FaceSplit lone = SplitFace(Points({false, false, false}, true, {false, true, true}));
  EXPECT_EQ(lone.triangles.size(), 3u);
  EXPECT_EQ(lone.trace.size(), 2u);  // to b and c
  EXPECT_EQ(lone.on_crack, (std::vector<std::array<VertexId, 3>>{{kInside, kB, kC}}));
}

TEST(FaceSplit, ThreeEdgePointsNeedAHub) {
  FacePoints p = Points({true, true, true});
  EXPECT_TRUE(NeedsHub(p));
  p.inside = kInside;
  EXPECT_FALSE(NeedsHub(p));
  EXPECT_EQ(SplitFace(p).trace.size(), 3u);
}

TEST(FaceSplit, AFaceWithItsCornersOnTheCrackLiesOnIt) {
  const FaceSplit two = SplitFace(Points({false, false, false}, false, {true, true, false}));
  EXPECT_EQ(two.trace, (std::vector<std::array<VertexId, 2>>{{kA, kB}}));
  EXPECT_TRUE(two.on_crack.empty());
  const FaceSplit three = SplitFace(Points({false, false, false}, false, {true, true, true}));
  EXPECT_EQ(three.trace.size(), 3u);
  EXPECT_EQ(three.on_crack.size(), 1u);
}

// An edge off the crack though its corners are on it (they came onto the crack from parts of the
// blade's path farther apart than the edge): no trace along it, and no triangle with it lies on
// the crack; a triangle through an inside point beside it still may.
TEST(FaceSplit, AnEdgeOffTheCrackIsNoTraceAndHoldsNoTriangleOnIt) {
  FacePoints whole = Points({false, false, false}, false, {true, true, true});
  whole.edge_on_crack = {true, false, true};  // B-C off
  const FaceSplit split = SplitFace(whole);
  EXPECT_EQ(split.trace, (std::vector<std::array<VertexId, 2>>{{kA, kB}, {kA, kC}}));
  EXPECT_TRUE(split.on_crack.empty());
  FacePoints fan = Points({false, false, false}, true, {true, true, true});
  fan.edge_on_crack = {true, false, true};
  const FaceSplit fanned = SplitFace(fan);
  EXPECT_EQ(fanned.on_crack.size(), 2u);
  for (const auto& t : fanned.on_crack) {
    EXPECT_FALSE(std::count(t.begin(), t.end(), kB) && std::count(t.begin(), t.end(), kC));
  }
}

// A triangle kept off the crack stays off it, in whatever order its vertices are named; the
// others at the face still lie on it, and the trace is the same.
TEST(FaceSplit, ATriangleKeptOffTheCrackIsNotOnIt) {
  FacePoints whole = Points({false, false, false}, false, {true, true, true});
  whole.kept_off = {{kC, kA, kB}};
  EXPECT_TRUE(SplitFace(whole).on_crack.empty());
  EXPECT_EQ(SplitFace(whole).trace.size(), 3u);
  FacePoints fan = Points({false, false, false}, true, {true, true, true});
  const FaceSplit on = SplitFace(fan);
  ASSERT_EQ(on.on_crack.size(), 3u);
  fan.kept_off = {{on.on_crack[1][2], on.on_crack[1][0], on.on_crack[1][1]}};
  const FaceSplit off = SplitFace(fan);
  EXPECT_EQ(off.on_crack, (std::vector<std::array<VertexId, 3>>{on.on_crack[0], on.on_crack[2]}));
  EXPECT_EQ(off.trace, on.trace);
}

}  // namespace
}  // namespace kerf::cut
