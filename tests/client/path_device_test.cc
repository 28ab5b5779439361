#include "haptic/path_device.h"

#include <gtest/gtest.h>

#include "haptic/keyboard_device.h"

namespace kerf::client {
namespace {

kerf::v1::BladePath TwoPoses() {
  kerf::v1::BladePath path;
  for (const double t : {1.0, 1.5}) {
    kerf::v1::BladePose& p = *path.add_poses();
    p.set_time(t);
    for (const double v : {t, 0.0, 0.0}) p.add_tip(v);
    for (const double v : {t, 0.0, 0.05}) p.add_heel(v);
  }
  return path;
}

TEST(PathDevice, FollowsThePathLinearlyFromItsStartAndEnds) {
  PathDevice device(TwoPoses());
  EXPECT_DOUBLE_EQ(device.Sample(0)->tip.x(), 1.0);
  EXPECT_DOUBLE_EQ(device.Sample(0.25)->tip.x(), 1.25);
  EXPECT_DOUBLE_EQ(device.Sample(0.25)->heel.z(), 0.05);
  EXPECT_TRUE(device.Sample(0.5).has_value());
  EXPECT_FALSE(device.Sample(0.5001).has_value());
  PathDevice slow(TwoPoses(), 4);
  EXPECT_DOUBLE_EQ(slow.Sample(1.0)->tip.x(), 1.25);
  EXPECT_FALSE(slow.Sample(2.01).has_value());
}

TEST(SimulatedHandDevice, TremblesAroundThePathByAboutItsAmplitude) {
  SimulatedHandDevice hand(TwoPoses(), 1, 1e-4, 7);
  PathDevice path(TwoPoses());
  double largest = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int samples = 0;
  for (double t = 0; t <= 0.5; t += 0.001, ++samples) {
    const BladeSample held = *hand.Sample(t), planned = *path.Sample(t);
    const Eigen::Vector3d tremble = held.tip - planned.tip;
    EXPECT_NEAR((held.heel - planned.heel - tremble).norm(), 0, 1e-12)
        << "a rigid blade: heel and tip move together";
    largest = std::max(largest, tremble.cwiseAbs().maxCoeff());
    sum += tremble;
  }
  EXPECT_GT(largest, 0.3e-4);                                // it trembles
  EXPECT_LT(largest, 2e-4);                                  // by about the amplitude
  EXPECT_LT((sum / samples).cwiseAbs().maxCoeff(), 0.3e-4);  // around the path
}

TEST(KeyboardDevice, KeysMoveTheBladeAMillimetre) {
  EXPECT_EQ(KeyMotion('w'), Eigen::Vector3d(0, 0.001, 0));
  EXPECT_EQ(KeyMotion('a'), Eigen::Vector3d(-0.001, 0, 0));
  EXPECT_EQ(KeyMotion('f'), Eigen::Vector3d(0, 0, -0.001));
  EXPECT_EQ(KeyMotion('x'), Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace kerf::client
