#include "haptic/force_model.h"

#include <algorithm>

namespace kerf::client {

void ForceModel::Update(double time, const Eigen::Vector3d& tip, const Eigen::Vector3d& force,
                        const Eigen::Vector3d& device_tip) {
  const Eigen::Vector3d rendered = At(time, device_tip);
  if (started_) {
    const Eigen::Vector3d dx = tip - current_.tip;
    if (dx.squaredNorm() > 1e-12) {  // moved more than 1 um: a new slope along the motion
      const double k = -(force - current_.force).dot(dx) / dx.squaredNorm();
      stiffness_ = 0.7 * stiffness_ + 0.3 * std::clamp(k, 0.0, options_.max_stiffness);
    }
  }
  current_ = {tip, force, options_.interpolate ? stiffness_ : 0};
  offset_ = rendered - current_.At(device_tip);  // zero before the first frame: from rest
  updated_at_ = time;
  started_ = true;
}

Eigen::Vector3d ForceModel::At(double time, const Eigen::Vector3d& tip) const {
  if (!started_) return Eigen::Vector3d::Zero();
  if (!options_.interpolate) return current_.force;
  const double fade = std::clamp(1 - (time - updated_at_) / options_.blend_seconds, 0.0, 1.0);
  return current_.At(tip) + fade * offset_;
}

}  // namespace kerf::client
