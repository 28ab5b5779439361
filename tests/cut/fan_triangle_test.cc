#include "cut/fan_triangle.h"

#include <gtest/gtest.h>

#include <vector>

namespace kerf::cut {
namespace {

// The face's corners and the middle of its first edge, around; the fan from the centroid.
const std::vector<Eigen::Vector3d> kBoundary = {{1, 0, 0}, {0.5, 0.5, 0}, {0, 1, 0}, {0, 0, 1}};
const Eigen::Vector3d kHub(1.0 / 3, 1.0 / 3, 1.0 / 3);

TEST(FanTriangle, ThePointIsInTheTriangleThatHoldsIt) {
  // Near corner 0, on the side of the edge's middle: the fan's triangle (hub, corner 0, middle).
  EXPECT_EQ(FanTriangleHolding(kBoundary, kHub, {0.6, 0.3, 0.1}, 1e-3), 0);
  EXPECT_EQ(FanTriangleHolding(kBoundary, kHub, {0.3, 0.6, 0.1}, 1e-3), 1);
  EXPECT_EQ(FanTriangleHolding(kBoundary, kHub, {0.1, 0.3, 0.6}, 1e-3), 2);
  EXPECT_EQ(FanTriangleHolding(kBoundary, kHub, {0.6, 0.1, 0.3}, 1e-3), 3);
}

TEST(FanTriangle, NoneWithinTheMarginOfTheFansEdgesOrOutside) {
  // On the fan's edge from the hub to the edge's middle (weights 0 and 1 equal).
  EXPECT_EQ(FanTriangleHolding(kBoundary, kHub, {0.4, 0.4, 0.2}, 1e-3), std::nullopt);
  // At the hub itself, and just beside it.
  EXPECT_EQ(FanTriangleHolding(kBoundary, kHub, kHub, 1e-3), std::nullopt);
  EXPECT_EQ(FanTriangleHolding(kBoundary, kHub, kHub + Eigen::Vector3d(2e-4, -1e-4, -1e-4), 1e-3),
            std::nullopt);
  // Outside the face.
  EXPECT_EQ(FanTriangleHolding(kBoundary, kHub, {1.2, -0.1, -0.1}, 1e-3), std::nullopt);
  // Beside the edge from the hub to the corner 0 by less than the margin, and more.
  EXPECT_EQ(FanTriangleHolding(kBoundary, kHub, {0.6, 0.2003, 0.1997}, 1e-2), std::nullopt);
  EXPECT_EQ(FanTriangleHolding(kBoundary, kHub, {0.6, 0.23, 0.17}, 1e-2), 0);
}

}  // namespace
}  // namespace kerf::cut
