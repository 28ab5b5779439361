#include "haptic/force_model.h"

#include <gtest/gtest.h>

namespace kerf::client {
namespace {

const Eigen::Vector3d kX0(0.01, 0.02, 0.0);

// Frames of a spring F = -k (x - x0) along +x, one per millisecond, the device 2 mm ahead of
// the pose each frame answers (latency): what the model renders on every 1 kHz tick.
std::vector<Eigen::Vector3d> Render(ForceModel& model, double k, int ticks) {
  std::vector<Eigen::Vector3d> rendered;
  for (int i = 0; i < ticks; ++i) {
    const double t = 0.001 * i;
    const Eigen::Vector3d frame_tip = kX0 + Eigen::Vector3d(0.01 * t, 0, 0);  // 1 cm/s
    const Eigen::Vector3d device_tip = frame_tip + Eigen::Vector3d(0.002, 0, 0);
    model.Update(t, frame_tip, -k * (frame_tip - kX0), device_tip);
    rendered.push_back(model.At(t, device_tip));
  }
  return rendered;
}

TEST(ForceModel, EstimatesTheTissuesStiffnessAlongTheMotion) {
  ForceModel model({});
  Render(model, 500, 50);
  EXPECT_NEAR(model.stiffness(), 500, 5);
  ForceModel steep({});
  Render(steep, 1e6, 50);
  EXPECT_NEAR(steep.stiffness(), 2000, 1e-3);  // clamped: a device could not render it stably
  ForceModel pulling({});
  Render(pulling, -500, 50);  // force growing with the motion: no negative spring
  EXPECT_DOUBLE_EQ(pulling.stiffness(), 0);
}

TEST(ForceModel, PredictsTheForceWhereTheDeviceIsNow) {
  ForceModel model({});
  const std::vector<Eigen::Vector3d> rendered = Render(model, 500, 60);
  // Once the stiffness is known, the force rendered is the spring's at the device's position
  // (2 mm ahead of the frames): -500 N/m * (x - x0) there.
  const double t = 0.059;
  const double x = 0.01 * t + 0.002;
  EXPECT_NEAR(rendered.back().x(), -500 * x, 0.02 * 500 * x);
}

TEST(ForceModel, TheRenderedForceIsContinuousWhenAFrameArrives) {
  ForceModel model({});
  const Eigen::Vector3d device_tip = kX0;
  model.Update(0, kX0, Eigen::Vector3d(1, 0, 0), device_tip);
  for (int i = 1; i <= 30; ++i) {  // a 0.5 N step in every frame, frames every 1 ms
    const double t = 0.001 * i;
    const Eigen::Vector3d before = model.At(t, device_tip);
    model.Update(t, kX0, Eigen::Vector3d(1 + 0.5 * i, 0, 0), device_tip);
    EXPECT_NEAR((model.At(t, device_tip) - before).norm(), 0, 1e-12) << "frame " << i;
  }
  // The first frame fades in from rest, and the model is reached after the blend time.
  ForceModel fresh({});
  fresh.Update(0, kX0, Eigen::Vector3d(4, 0, 0), device_tip);
  EXPECT_NEAR(fresh.At(0, device_tip).norm(), 0, 1e-12);
  EXPECT_NEAR(fresh.At(0.005, device_tip).x(), 2, 1e-9);
  EXPECT_NEAR(fresh.At(0.010, device_tip).x(), 4, 1e-9);
}

TEST(ForceModel, WithoutInterpolationTheLastFrameIsHeld) {
  ForceModel::Options options;
  options.interpolate = false;
  ForceModel model(options);
  model.Update(0, kX0, Eigen::Vector3d(1, 2, 3), kX0);
  EXPECT_EQ(model.At(0, kX0 + Eigen::Vector3d(0.01, 0, 0)), Eigen::Vector3d(1, 2, 3));
  model.Update(0.01, kX0, Eigen::Vector3d(4, 0, 0), kX0);
  EXPECT_EQ(model.At(0.01, kX0), Eigen::Vector3d(4, 0, 0));  // the step, at once
}

}  // namespace
}  // namespace kerf::client
