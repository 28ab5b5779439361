#include "cut/face_point_weights.h"

#include <gtest/gtest.h>

#include <random>

namespace kerf::cut {
namespace {

constexpr double kShare = 0.2;

TEST(FacePointOffEdges, APointOffTheEdgesStaysWhereItIs) {
  const Eigen::Vector3d b(0.3, 0.3, 0.4);
  EXPECT_EQ(FacePointOffEdges(b, kShare), b);
}

// Near one edge (the corner 0's weight small): that weight becomes the share, the two others
// keep their ratio.
TEST(FacePointOffEdges, APointNearAnEdgeMovesOffItByTheShare) {
  const Eigen::Vector3d w = FacePointOffEdges(Eigen::Vector3d(0.05, 0.5, 0.45), kShare);
  EXPECT_DOUBLE_EQ(w[0], kShare);
  EXPECT_NEAR(w[1] / w[2], 0.5 / 0.45, 1e-12);
  EXPECT_NEAR(w.sum(), 1, 1e-12);
}

// Near a corner (two weights small, as a crossing of the face beside corner 1): off the nearer
// edge by about the share, off the other by half of it, the corner's weight the largest still.
TEST(FacePointOffEdges, APointNearACornerMovesOffBothEdges) {
  const Eigen::Vector3d w = FacePointOffEdges(Eigen::Vector3d(0.02, 0.93, 0.05), kShare);
  EXPECT_GE(w[0], 0.9 * kShare);
  EXPECT_DOUBLE_EQ(w[2], kShare / 2);
  EXPECT_NEAR(w.sum(), 1, 1e-12);
  EXPECT_GT(w[1], 0.6);
}

TEST(FacePointOffEdges, AShareOverAThirdIsAThird) {
  const Eigen::Vector3d w = FacePointOffEdges(Eigen::Vector3d(1, 0, 0), 0.9);
  EXPECT_NEAR(w.minCoeff(), 1.0 / 6, 1e-12);
  EXPECT_NEAR(w.sum(), 1, 1e-12);
  EXPECT_GE(w.minCoeff(), 0);
}

// Any weights on a face, on its edges and corners too: a point of the face (the weights sum to
// 1), off every edge by half the share at least, and no farther from the original point than
// it needs: a weight already at the share or more never grows.
TEST(FacePointOffEdges, AnyPointEndsInsideTheFaceOffItsEdges) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int trial = 0; trial < 1000; ++trial) {
    Eigen::Vector3d b(unit(random), unit(random), unit(random));
    if (trial % 4 == 0) b[trial % 3] = 0;        // on an edge
    if (trial % 8 == 0) b[(trial + 1) % 3] = 0;  // at a corner
    b /= b.sum();
    const double share = 0.05 + 0.25 * unit(random);
    const Eigen::Vector3d w = FacePointOffEdges(b, share);
    SCOPED_TRACE(::testing::Message() << "b " << b.transpose() << " share " << share);
    EXPECT_NEAR(w.sum(), 1, 1e-12);
    EXPECT_GE(w.minCoeff(), share / 2 - 1e-12);
    for (int k = 0; k < 3; ++k) {
      if (b[k] >= share) {
        EXPECT_LE(w[k], b[k] + 1e-12);
      }
    }
  }
}

}  // namespace
}  // namespace kerf::cut
