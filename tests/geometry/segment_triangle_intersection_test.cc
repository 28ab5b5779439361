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

TEST(IntersectSegmentTriangle, ASegmentInThePlaneUpToRoundingMissesIt) {
  // A blade laid in the plane of a liver's face (a path of the face-plane family): its ends lie
  // about 1e-17 of the face's side of the plane, with signs that would say it crosses the face's
  // edge at a quarter, 0.8 of an edge away from the segment.
  const Vector3d a(-2.9164300000000001, 3.1646999999999998, 0.59366399999999997);
  const Vector3d b(-3.1878600000000001, 3.5354199999999998, 0.94919900000000001);
  const Vector3d c(-2.6046, 3.74729, 1.1957100000000001);
  const Vector3d p(-3.3386034903776709, 2.9077945461283674, 0.31147833116981893);
  const Vector3d q(-2.9192761166090575, 10.069540515014868, 7.5121052340832355);
  EXPECT_FALSE(IntersectSegmentTriangle(p, q, a, b, c));
  // One nearly in the plane but crossing it, a millionth of its length from it at its ends, does.
  const auto shallow = IntersectSegmentTriangle({-1, 0.2, -1e-6}, {2, 0.2, 1e-6}, kA, kB, kC);
  ASSERT_TRUE(shallow.has_value());
  EXPECT_NEAR(shallow->t, 0.5, 1e-12);
  EXPECT_TRUE(shallow->barycentric.isApprox(Vector3d(0.3, 0.5, 0.2), 1e-9)) << shallow->barycentric;
}

}  // namespace
}  // namespace kerf::geometry
