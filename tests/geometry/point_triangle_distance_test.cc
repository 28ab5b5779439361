#include "geometry/point_triangle_distance.h"

#include <gtest/gtest.h>

#include <random>

namespace kerf::geometry {
namespace {

const Eigen::Vector3d kCornerA(0, 0, 0), kCornerB(4, 0, 0), kCornerC(0, 4, 0);

TEST(DistanceToTriangle, AboveTheInsideIsTheHeight) {
  EXPECT_DOUBLE_EQ(DistanceToTriangle({1, 1, 3}, kCornerA, kCornerB, kCornerC), 3);
  EXPECT_DOUBLE_EQ(DistanceToTriangle({1, 1, 0}, kCornerA, kCornerB, kCornerC), 0);  // on it
}

TEST(DistanceToTriangle, BesideAnEdgeIsToTheEdge) {
  EXPECT_DOUBLE_EQ(DistanceToTriangle({2, -3, 4}, kCornerA, kCornerB, kCornerC), 5);  // beside ab
  EXPECT_DOUBLE_EQ(DistanceToTriangle({-3, 2, 4}, kCornerA, kCornerB, kCornerC), 5);  // beside ac
  EXPECT_NEAR(DistanceToTriangle({3, 3, 0}, kCornerA, kCornerB, kCornerC), std::sqrt(2.0),
              1e-15);  // beside bc
}

TEST(DistanceToTriangle, PastACornerIsToTheCorner) {
  EXPECT_DOUBLE_EQ(DistanceToTriangle({-3, -4, 0}, kCornerA, kCornerB, kCornerC), 5);
  EXPECT_DOUBLE_EQ(DistanceToTriangle({7, -4, 0}, kCornerA, kCornerB, kCornerC), 5);
  EXPECT_DOUBLE_EQ(DistanceToTriangle({-4, 7, 0}, kCornerA, kCornerB, kCornerC), 5);
}

TEST(DistanceToTriangle, ADegenerateTriangleIsItsSegment) {
  EXPECT_DOUBLE_EQ(DistanceToTriangle({2, 3, 4}, kCornerA, kCornerB, {2, 0, 0}), 5);
  EXPECT_DOUBLE_EQ(DistanceToTriangle({0, 3, 4}, kCornerA, kCornerA, kCornerA), 5);
}

TEST(ClosestPointOnTriangle, NoPointOfTheTriangleIsCloser) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> coordinate(-6, 6), weight(0, 1);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d x(coordinate(random), coordinate(random), coordinate(random));
    const Eigen::Vector3d a(coordinate(random), coordinate(random), coordinate(random));
    const Eigen::Vector3d b(coordinate(random), coordinate(random), coordinate(random));
    const Eigen::Vector3d c(coordinate(random), coordinate(random), coordinate(random));
    const double d = DistanceToTriangle(x, a, b, c);
    for (int k = 0; k < 20; ++k) {
      double u = weight(random), v = weight(random);
      if (u + v > 1) u = 1 - u, v = 1 - v;
      const Eigen::Vector3d p = a + u * (b - a) + v * (c - a);
      ASSERT_LE(d, (x - p).norm() + 1e-12) << "sample " << i;
    }
  }
}

}  // namespace
}  // namespace kerf::geometry
