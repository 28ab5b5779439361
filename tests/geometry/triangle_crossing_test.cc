#include "geometry/triangle_crossing.h"

#include <gtest/gtest.h>

namespace kerf::geometry {
namespace {

using Eigen::Vector3d;

const Vector3d kFloorA(0, 0, 0), kFloorB(2, 0, 0), kFloorC(0, 2, 0);

// Whether {p, q} is the segment {u, v}, either way round.
bool SameSegment(const std::array<Vector3d, 2>& s, const Vector3d& u, const Vector3d& v) {
  return (s[0].isApprox(u, 1e-12) && s[1].isApprox(v, 1e-12)) ||
         (s[0].isApprox(v, 1e-12) && s[1].isApprox(u, 1e-12));
}

TEST(TrianglesCross, AnUprightTriangleThroughTheFloorCrossesAlongItsCut) {
  // Standing in x = 0.5, through the floor triangle from y = -1 to y = 1 (its edge ends the
  // crossing at y = 0 on one side, its own edge at y = 1 on the other).
  const auto s =
      TrianglesCross(kFloorA, kFloorB, kFloorC, {0.5, -1, -1}, {0.5, 1, -1}, {0.5, 1, 1});
  ASSERT_TRUE(s.has_value());
  EXPECT_TRUE(SameSegment(*s, {0.5, 0, 0}, {0.5, 1, 0}))
      << (*s)[0].transpose() << " / " << (*s)[1].transpose();
  // Either order of the triangles.
  const auto t =
      TrianglesCross({0.5, -1, -1}, {0.5, 1, -1}, {0.5, 1, 1}, kFloorA, kFloorB, kFloorC);
  ASSERT_TRUE(t.has_value());
  EXPECT_TRUE(SameSegment(*t, {0.5, 0, 0}, {0.5, 1, 0}));
}

TEST(TrianglesCross, TrianglesTouchingAtAPointMeetThere) {
  const auto s = TrianglesCross(kFloorA, kFloorB, kFloorC, {0, 0, 0}, {-1, 0, 1}, {0, -1, 1});
  ASSERT_TRUE(s.has_value());
  EXPECT_TRUE(SameSegment(*s, kFloorA, kFloorA));
}

TEST(TrianglesCross, ApartOrInOnePlaneTheyDoNot) {
  EXPECT_FALSE(TrianglesCross(kFloorA, kFloorB, kFloorC, {0.5, 0.5, 1}, {1, 0.5, 1}, {0.5, 1, 2})
                   .has_value());
  // Above the floor's plane, standing beside the triangle (its plane crosses the floor's outside
  // the triangle).
  EXPECT_FALSE(
      TrianglesCross(kFloorA, kFloorB, kFloorC, {3, -1, -1}, {3, 1, -1}, {3, 1, 1}).has_value());
  EXPECT_FALSE(TrianglesCross(kFloorA, kFloorB, kFloorC, {0.1, 0.1, 0}, {1, 0.1, 0}, {0.1, 1, 0})
                   .has_value());
}

}  // namespace
}  // namespace kerf::geometry
