#include "geometry/segment_triangle_intersection.h"

#include <gtest/gtest.h>

namespace kerf::geometry {
namespace {

using Eigen::Vector3d;

const Vector3d kA(0, 0, 0), kB(1, 0, 0), kC(0, 1, 0);

TEST(IntersectSegmentTriangle, CrossingInsideGivesParameterAndBarycentrics) {
  const auto hit = IntersectSegmentTriangle({0.2, 0.3, -1}, {0.2, 0.3, 3}, kA, kB, kC);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t, 0.25, 1e-15);
  EXPECT_TRUE(hit->barycentric.isApprox(Vector3d(0.5, 0.2, 0.3), 1e-14)) << hit->barycentric;
}

TEST(IntersectSegmentTriangle, BoundariesCount) {
  // Through an edge, through a corner, and a segment ending on the triangle.
  ASSERT_TRUE(IntersectSegmentTriangle({0.5, 0, -1}, {0.5, 0, 1}, kA, kB, kC).has_value());
  const auto corner = IntersectSegmentTriangle({0, 0, -1}, {0, 0, 1}, kA, kB, kC);
  ASSERT_TRUE(corner.has_value());
  EXPECT_TRUE(corner->barycentric.isApprox(Vector3d(1, 0, 0)));
  const auto ending = IntersectSegmentTriangle({0.1, 0.1, -1}, {0.1, 0.1, 0}, kA, kB, kC);
  ASSERT_TRUE(ending.has_value());
  EXPECT_EQ(ending->t, 1.0);
}

TEST(IntersectSegmentTriangle, MissesAndDegenerateCases) {
  EXPECT_FALSE(IntersectSegmentTriangle({0.8, 0.8, -1}, {0.8, 0.8, 1}, kA, kB, kC));  // outside
  EXPECT_FALSE(IntersectSegmentTriangle({0.2, 0.2, 1}, {0.2, 0.2, 2}, kA, kB, kC));   // above
  EXPECT_FALSE(IntersectSegmentTriangle({-1, 0.2, 0}, {2, 0.2, 0}, kA, kB, kC));      // in plane
  EXPECT_FALSE(IntersectSegmentTriangle({0.2, 0.2, -1}, {0.2, 0.2, 1}, kA, kB, kA));  // flat
}

}  // namespace
}  // namespace kerf::geometry
