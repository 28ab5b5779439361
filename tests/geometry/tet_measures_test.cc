#include "geometry/tet_measures.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kerf::geometry {
namespace {

using Eigen::Vector3d;

const Vector3d kO(0, 0, 0), kX(1, 0, 0), kY(0, 1, 0), kZ(0, 0, 1);

TEST(SignedVolume, UnitCornerTetIsOneSixthAndFlipsWithOrientation) {
  EXPECT_DOUBLE_EQ(SignedVolume(kO, kX, kY, kZ), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(SignedVolume(kO, kY, kX, kZ), -1.0 / 6.0);
  EXPECT_DOUBLE_EQ(SignedVolume(kO, kX, kY, Vector3d(0.3, 0.3, 0)), 0.0);
}

TEST(SmallestHeight, IsTheCornerOppositeTheLargestFaceAndZeroWhenFlat) {
  // The unit corner tet: the origin is 1/sqrt(3) from the slanted face, the others 1 away.
  EXPECT_NEAR(SmallestHeight(kO, kX, kY, kZ), 1 / std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(SmallestHeight(kX, kO, kY, kZ), 1 / std::sqrt(3.0), 1e-15);  // orientation-free
  // Squashed to a thousandth along z (the slanted face is the largest), and flat.
  EXPECT_NEAR(SmallestHeight(kO, kX, kY, 0.001 * kZ), 0.001 / std::sqrt(1 + 2e-6), 1e-15);
  EXPECT_EQ(SmallestHeight(kO, kX, kY, Vector3d(0.3, 0.3, 0)), 0);
}

TEST(ContainsPoint, InsideAndOnTheBoundaryButNotOutsideInEitherOrientation) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
  for (const bool flipped : {false, true}) {
    const Eigen::Vector3d& p = flipped ? c : b;
    const Eigen::Vector3d& q = flipped ? b : c;
    EXPECT_TRUE(ContainsPoint(a, p, q, d, {0.2, 0.2, 0.2}));
    EXPECT_TRUE(ContainsPoint(a, p, q, d, {0.5, 0.5, 0}));  // on a face
    EXPECT_TRUE(ContainsPoint(a, p, q, d, a));              // a corner
    EXPECT_FALSE(ContainsPoint(a, p, q, d, {0.5, 0.5, 0.1}));
    EXPECT_FALSE(ContainsPoint(a, p, q, d, {-0.01, 0.2, 0.2}));
  }
}

TEST(BarycentricWeights, RebuildThePointAndAreTheCornersOwnAtTheCorners) {
  const Vector3d a(0.1, 0, 0), b(1, 0.2, 0), c(0, 1, 0.1), d(0.2, 0.3, 1);
  EXPECT_TRUE(BarycentricWeights(a, b, c, d, c).isApprox(Eigen::Vector4d(0, 0, 1, 0)));
  const Vector3d p(0.3, 0.25, 0.4);
  const Eigen::Vector4d w = BarycentricWeights(a, b, c, d, p);
  EXPECT_NEAR(w.sum(), 1, 1e-15);
  EXPECT_TRUE((w[0] * a + w[1] * b + w[2] * c + w[3] * d).isApprox(p, 1e-14));
  EXPECT_LT(BarycentricWeights(a, b, c, d, Vector3d(2, 2, 2)).minCoeff(), 0);  // outside
}

TEST(DihedralAngles, CornerTetHasThreeRightAnglesAndThreeOf54_7) {
  // Edges at the origin (ab, ac, ad) have 90 degrees; the far edges have
  // acos(1/sqrt(3)) = 54.7356 degrees.
  const std::array<double, 6> angles = DihedralAnglesDeg(kO, kX, kY, kZ);
  const double far = std::acos(1 / std::sqrt(3.0)) * 180 / M_PI;
  for (int e = 0; e < 3; ++e) EXPECT_NEAR(angles[e], 90.0, 1e-12) << e;
  for (int e = 3; e < 6; ++e) EXPECT_NEAR(angles[e], far, 1e-12) << e;
}

TEST(SmallestDihedral, IsTheLeastOfTheSixAngles) {
  EXPECT_NEAR(SmallestDihedralDeg(kO, kX, kY, kZ), std::acos(1 / std::sqrt(3.0)) * 180 / M_PI,
              1e-12);
}

TEST(MeanEdgeLength, IsTheMeanOfTheSixEdges) {
  // Three edges of 1 at the corner, three of sqrt 2 across.
  EXPECT_NEAR(MeanEdgeLength(kO, kX, kY, kZ), (3 + 3 * std::sqrt(2.0)) / 6, 1e-15);
  EXPECT_NEAR(MeanEdgeLength(2 * kO, 2 * kX, 2 * kY, 2 * kZ), 1 + std::sqrt(2.0), 1e-15);
}

TEST(DihedralAngles, RegularTetHasAllAnglesArccosOneThird) {
  const Vector3d a(1, 1, 1), b(1, -1, -1), c(-1, 1, -1), d(-1, -1, 1);
  for (const double angle : DihedralAnglesDeg(a, b, c, d)) {
    EXPECT_NEAR(angle, std::acos(1.0 / 3.0) * 180 / M_PI, 1e-12);  // 70.5288
  }
}

TEST(RadiusRatio, IsOneForRegularZeroForFlatAndIgnoresOrientation) {
  const Vector3d a(1, 1, 1), b(1, -1, -1), c(-1, 1, -1), d(-1, -1, 1);
  EXPECT_NEAR(RadiusRatio(a, b, c, d), 1.0, 1e-12);
  EXPECT_NEAR(RadiusRatio(a, c, b, d), 1.0, 1e-12);
  EXPECT_EQ(RadiusRatio(kO, kX, kY, Vector3d(1, 1, 0)), 0.0);
  // Corner tet: r_in = 1 / (3 + sqrt 3), r_circ = sqrt(3) / 2.
  EXPECT_NEAR(RadiusRatio(kO, kX, kY, kZ), 3 * (1 / (3 + std::sqrt(3.0))) / (std::sqrt(3.0) / 2),
              1e-12);
}

TEST(MeasureTet, SliverHasTinyMinimumAngle) {
  // Four nearly coplanar points: a square with one corner lifted by 1e-3.
  const TetMeasures m = MeasureTet(kO, kX, Vector3d(1, 1, 1e-3), kY);
  EXPECT_LT(m.min_dihedral_deg, 1.0);
  EXPECT_GT(m.max_dihedral_deg, 179.0);
  EXPECT_NEAR(m.min_edge_length, 1.0, 1e-12);
  EXPECT_NEAR(m.max_edge_length, std::sqrt(2.0), 1e-6);
}

}  // namespace
}  // namespace kerf::geometry
