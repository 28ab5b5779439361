#include "haptic/path_device.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kerf::client {

PathDevice::PathDevice(const kerf::v1::BladePath& path, double slowdown) {
  for (const kerf::v1::BladePose& p : path.poses()) {
    times_.push_back(slowdown * (p.time() - path.poses(0).time()));
    poses_.push_back({{p.tip(0), p.tip(1), p.tip(2)}, {p.heel(0), p.heel(1), p.heel(2)}});
  }
}

std::optional<BladeSample> PathDevice::Sample(double time) {
  if (time > times_.back()) return std::nullopt;
  const auto after = std::upper_bound(times_.begin(), times_.end(), time);
  if (after == times_.begin()) return poses_.front();
  if (after == times_.end()) return poses_.back();
  const std::size_t i = static_cast<std::size_t>(after - times_.begin());
  const double s = (time - times_[i - 1]) / (times_[i] - times_[i - 1]);
  return BladeSample{poses_[i - 1].tip + s * (poses_[i].tip - poses_[i - 1].tip),
                     poses_[i - 1].heel + s * (poses_[i].heel - poses_[i - 1].heel)};
}

SimulatedHandDevice::SimulatedHandDevice(const kerf::v1::BladePath& path, double slowdown,
                                         double amplitude, unsigned seed)
    : motion_(path, slowdown), amplitude_(amplitude), random_(seed) {
  std::uniform_real_distribution<double> phase(0, 2 * std::numbers::pi), hz(8, 12);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      phase_(i, j) = phase(random_);
      frequency_(i, j) = hz(random_);
    }
  }
}

std::optional<BladeSample> SimulatedHandDevice::Sample(double time) {
  std::optional<BladeSample> sample = motion_.Sample(time);
  if (!sample) return sample;
  Eigen::Vector3d tremble;
  for (int axis = 0; axis < 3; ++axis) {
    double x = 0.1 * noise_(random_);
    for (int j = 0; j < 3; ++j) {
      x += std::sin(2 * std::numbers::pi * frequency_(axis, j) * time + phase_(axis, j)) / 3;
    }
    tremble[axis] = amplitude_ * x;
  }
  sample->tip += tremble;  // the hand holds the blade rigidly: both ends move together
  sample->heel += tremble;
  return sample;
}

}  // namespace kerf::client
