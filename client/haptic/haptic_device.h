// A haptic device: where the user's hand holds the blade, and the force to render on it.
//
// kerf-haptic's force loop calls Sample() and then Render() once per tick (1 kHz), on its own
// thread; neither may block. To add a real device (a Phantom/Touch, a Novint Falcon, ...),
// implement this interface over its driver: Sample() reads the stylus pose (converted to the
// scene's metres, the tip and the heel of the blade), Render() commands the force (N, clamped
// to what the device can exert), and add it to MakeDevice() in kerf_haptic_main.cc.
#pragma once

#include <Eigen/Core>
#include <optional>

namespace kerf::client {

struct BladeSample {
  Eigen::Vector3d tip;   // m
  Eigen::Vector3d heel;  // m
};

class HapticDevice {
 public:
  virtual ~HapticDevice() = default;
  // The blade at `time` s since the loop started; nullopt when the user is done.
  virtual std::optional<BladeSample> Sample(double time) = 0;
  // The force on the user's hand, N.
  virtual void Render(const Eigen::Vector3d& force) = 0;
};

}  // namespace kerf::client
