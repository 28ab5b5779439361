#include "haptic/keyboard_device.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>

namespace kerf::client {

Eigen::Vector3d KeyMotion(char key) {
  constexpr double kStep = 0.001;
  switch (key) {
    case 'd':
      return {kStep, 0, 0};
    case 'a':
      return {-kStep, 0, 0};
    case 'w':
      return {0, kStep, 0};
    case 's':
      return {0, -kStep, 0};
    case 'r':
      return {0, 0, kStep};
    case 'f':
      return {0, 0, -kStep};
    default:
      return Eigen::Vector3d::Zero();
  }
}

KeyboardDevice::KeyboardDevice(const BladeSample& start) : blade_(start) {
  if (isatty(STDIN_FILENO) && tcgetattr(STDIN_FILENO, &saved_) == 0) {
    termios raw = saved_;
    raw.c_lflag &= ~static_cast<tcflag_t>(ICANON | ECHO);
    raw.c_cc[VMIN] = 0;
    raw.c_cc[VTIME] = 0;
    raw_ = tcsetattr(STDIN_FILENO, TCSANOW, &raw) == 0;
  }
  fcntl(STDIN_FILENO, F_SETFL, fcntl(STDIN_FILENO, F_GETFL) | O_NONBLOCK);
}

KeyboardDevice::~KeyboardDevice() {
  if (raw_) tcsetattr(STDIN_FILENO, TCSANOW, &saved_);
}

std::optional<BladeSample> KeyboardDevice::Sample(double time) {
  char key;
  while (!done_ && read(STDIN_FILENO, &key, 1) == 1) {
    if (key == 'q') done_ = true;
    blade_.tip += KeyMotion(key);
    blade_.heel += KeyMotion(key);
  }
  if (time - shown_at_ >= 0.2) {  // five times a second, where the blade is and what it feels
    std::fprintf(stderr, "\rtip %+.3f %+.3f %+.3f m  force %+.2f %+.2f %+.2f N   ", blade_.tip.x(),
                 blade_.tip.y(), blade_.tip.z(), force_.x(), force_.y(), force_.z());
    shown_at_ = time;
  }
  if (done_) return std::nullopt;
  return blade_;
}

void KeyboardDevice::Render(const Eigen::Vector3d& force) { force_ = force; }

}  // namespace kerf::client
