// The keyboard in a terminal, as the paper drove its blade: w/s move it along +y/-y, d/a along
// +x/-x, r/f along +z/-z, 1 mm per key press; q ends. The terminal is put in raw,
// non-blocking mode while the device lives.
#pragma once

#include <termios.h>

#include "haptic/haptic_device.h"

namespace kerf::client {

// How a key moves the blade (m); zero for other keys.
Eigen::Vector3d KeyMotion(char key);

class KeyboardDevice : public HapticDevice {
 public:
  // Starts with the blade at `start`. Reads keys from standard input.
  explicit KeyboardDevice(const BladeSample& start);
  ~KeyboardDevice() override;
  std::optional<BladeSample> Sample(double time) override;
  void Render(const Eigen::Vector3d& force) override;

 private:
  BladeSample blade_;
  bool done_ = false;
  bool raw_ = false;
  termios saved_{};
  double shown_at_ = -1;
  Eigen::Vector3d force_ = Eigen::Vector3d::Zero();
};

}  // namespace kerf::client
