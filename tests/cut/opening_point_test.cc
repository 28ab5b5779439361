#include "cut/opening_point.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace kerf::cut {
namespace {

// An equilateral face in z = 0, its corner 2 opposite edge 0-1.
const std::array<Eigen::Vector3d, 3> kFace = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                              Eigen::Vector3d(0.5, std::sqrt(0.75), 0)};

Eigen::Vector3d PointAt(const Eigen::Vector3d& weights) {
  return weights[0] * kFace[0] + weights[1] * kFace[1] + weights[2] * kFace[2];
}

TEST(OpeningPoint, ASymmetricFaceOpensAtItsCentroid) {
  const Eigen::Vector3d centroid = PointAt(Eigen::Vector3d::Constant(1.0 / 3));
  const std::vector<Eigen::Vector3d> apexes = {centroid + Eigen::Vector3d(0, 0, 0.8),
                                               centroid - Eigen::Vector3d(0, 0, 0.8)};
  const Eigen::Vector3d weights = OpeningPointWeights(kFace, apexes);
  EXPECT_TRUE(weights.isApprox(Eigen::Vector3d::Constant(1.0 / 3))) << weights.transpose();
}

// A flat face (its corner 2 near edge 0-1): from the centroid, the fan tets over edge 0-1 have
// a thin base; the point leaning towards corner 2 balances the three.
TEST(OpeningPoint, AFlatFaceOpensNearerItsFarCorner) {
  const std::array<Eigen::Vector3d, 3> face = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                               Eigen::Vector3d(0.5, 0.1, 0)};
  const std::vector<Eigen::Vector3d> apexes = {Eigen::Vector3d(0.5, 0.03, 0.5),
                                               Eigen::Vector3d(0.5, 0.03, -0.5)};
  const Eigen::Vector3d weights = OpeningPointWeights(face, apexes);
  EXPECT_TRUE(weights.isApprox(Eigen::Vector3d(0.25, 0.25, 0.5))) << weights.transpose();
  const auto at = [&](const Eigen::Vector3d& w) {
    return w[0] * face[0] + w[1] * face[1] + w[2] * face[2];
  };
  const double centroid_angle =
      SmallestFanAngleDeg(face, at(Eigen::Vector3d::Constant(1.0 / 3)), apexes);
  const double chosen_angle = SmallestFanAngleDeg(face, at(weights), apexes);
  EXPECT_GT(chosen_angle, centroid_angle + 1)
      << "centroid " << centroid_angle << " deg, chosen " << chosen_angle << " deg";
}

// Whatever the apexes, the point is strictly inside the face and no worse than the centroid.
TEST(OpeningPoint, ThePointIsInsideTheFaceAndNoWorseThanTheCentroid) {
  for (int i = 0; i < 50; ++i) {
    std::vector<Eigen::Vector3d> apexes = {Eigen::Vector3d::Random(), Eigen::Vector3d::Random()};
    apexes[0].z() = 0.05 + std::abs(apexes[0].z());
    apexes[1].z() = -0.05 - std::abs(apexes[1].z());
    const Eigen::Vector3d weights = OpeningPointWeights(kFace, apexes);
    EXPECT_NEAR(weights.sum(), 1, 1e-12);
    EXPECT_GT(weights.minCoeff(), 0.1);
    EXPECT_GE(SmallestFanAngleDeg(kFace, PointAt(weights), apexes),
              SmallestFanAngleDeg(kFace, PointAt(Eigen::Vector3d::Constant(1.0 / 3)), apexes));
  }
}

}  // namespace
}  // namespace kerf::cut
