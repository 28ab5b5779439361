#include "cut/blade.h"

#include <gtest/gtest.h>

#include <limits>

#include "support/status_message.h"

namespace kerf::cut {
namespace {

using kerf::testing::StatusMessage;

TEST(InterpolatePose, MovesTipAndHeelLinearlyInTime) {
  const BladePose a{1.0, {0, 0, 0}, {0, 0, 0.02}};
  const BladePose b{1.5, {0.01, 0.002, 0}, {0.01, 0, 0.03}};
  const BladePose at_a = InterpolatePose(a, b, 1.0);
  EXPECT_EQ(at_a.tip, a.tip);
  EXPECT_EQ(at_a.heel, a.heel);
  const BladePose middle = InterpolatePose(a, b, 1.25);
  EXPECT_EQ(middle.time, 1.25);
  EXPECT_TRUE(middle.tip.isApprox(Eigen::Vector3d(0.005, 0.001, 0), 1e-15));
  EXPECT_TRUE(middle.heel.isApprox(Eigen::Vector3d(0.005, 0, 0.025), 1e-15));
}

TEST(ValidatePose, RefusesNonFiniteShortLongJumpingAndFastPoses) {
  const BladeLimits limits;  // 0.1 m long, 0.02 m per pose, 2 m/s
  const BladePose first{0, {0, 0, 0}, {0, 0, 0.02}};
  EXPECT_TRUE(ValidatePose(first, nullptr, limits).ok());
  BladePose p = first;
  p.tip.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(StatusMessage(ValidatePose(p, nullptr, limits)),
            "the pose has a non-finite time, tip or heel");
  p = first;
  p.heel = p.tip;
  EXPECT_EQ(StatusMessage(ValidatePose(p, nullptr, limits)),
            "the blade is 0 m long; it must be longer than 0 and at most 0.1 m");
  p = first;
  p.heel.z() = 0.5;
  EXPECT_EQ(StatusMessage(ValidatePose(p, nullptr, limits)),
            "the blade is 0.5 m long; it must be longer than 0 and at most 0.1 m");
  p = {1, {0.05, 0, 0}, {0.05, 0, 0.02}};
  EXPECT_EQ(StatusMessage(ValidatePose(p, &first, limits)),
            "the blade jumps 0.05 m in one pose; at most 0.02 m is accepted");
  p = {0.001, {0.01, 0, 0}, {0.01, 0, 0.02}};
  EXPECT_EQ(StatusMessage(ValidatePose(p, &first, limits)),
            "the blade moves at 10 m/s; at most 2 m/s is accepted");
  p = {0.01, {0.01, 0, 0}, {0.01, 0, 0.02}};
  EXPECT_TRUE(ValidatePose(p, &first, limits).ok());
}

// A blade standing along z, moved 1 along x: it sweeps the unit square of the plane y = 0.
TEST(Blade, TheSweepIsTheSquareBetweenTwoPoses) {
  const BladePose from{0, {0, 0, 0}, {0, 0, 1}}, to{0.1, {1, 0, 0}, {1, 0, 1}};
  const auto triangles = SweptTriangles(from, to);
  EXPECT_EQ(triangles[0][0], from.tip);
  EXPECT_EQ(triangles[1][2], to.tip);
  EXPECT_DOUBLE_EQ(DistanceToSweep({0.5, 0.3, 0.5}, from, to), 0.3);  // over its middle
  EXPECT_DOUBLE_EQ(DistanceToSweep({0.1, 0, 0.9}, from, to), 0);      // in it, by the heel
  EXPECT_DOUBLE_EQ(DistanceToSweep({2, 0, 0.5}, from, to), 1);        // beyond its far side
}

}  // namespace
}  // namespace kerf::cut
