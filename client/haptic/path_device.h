// Devices that play a recorded motion: a blade path file (the `kerf cut` format), followed
// exactly (linear between poses), or as a hand holding it would at 1 kHz, with tremble.
#pragma once

#include <random>
#include <vector>

#include "haptic/haptic_device.h"
#include "kerf/v1/blade.pb.h"

namespace kerf::client {

class PathDevice : public HapticDevice {
 public:
  // `path` has at least one pose (times increasing); played `slowdown` times slower.
  explicit PathDevice(const kerf::v1::BladePath& path, double slowdown = 1);
  std::optional<BladeSample> Sample(double time) override;
  void Render(const Eigen::Vector3d&) override {}

 private:
  std::vector<double> times_;
  std::vector<BladeSample> poses_;
};

// Physiological tremor: a few sinusoids between 8 and 12 Hz per axis with random phases, and
// white noise, of about `amplitude` m in all (0.1 mm is typical of a steady surgeon's hand).
class SimulatedHandDevice : public HapticDevice {
 public:
  SimulatedHandDevice(const kerf::v1::BladePath& path, double slowdown, double amplitude,
                      unsigned seed);
  std::optional<BladeSample> Sample(double time) override;
  void Render(const Eigen::Vector3d&) override {}

 private:
  PathDevice motion_;
  double amplitude_;
  std::mt19937 random_;
  std::normal_distribution<double> noise_{0.0, 1.0};
  Eigen::Matrix3d phase_, frequency_;  // per axis, per sinusoid
};

}  // namespace kerf::client
