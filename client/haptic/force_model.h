// The force the device renders between server frames. Each cutter frame gives the tool force
// F_k with the blade where the pose it answers put it (tip x_k). Between frames the force is a
// local linear model around the last of them, F(x) = F_k - k (x - x_k), with the tissue's
// stiffness k (N/m, a scalar) estimated from successive frames along the blade's motion. When
// a frame arrives, the difference between the force rendered at that moment and the new
// model's is kept as an offset that fades to zero over `blend_seconds`: the rendered force is
// continuous however often frames come. Without interpolation it is the last frame's force
// held (what a device fed directly at the frame rate feels).
#pragma once

#include <Eigen/Core>

namespace kerf::client {

class ForceModel {
 public:
  struct Options {
    bool interpolate = true;
    double blend_seconds = 0.01;
    double max_stiffness = 2000;  // N/m, for stability of a device rendering it
  };
  explicit ForceModel(Options options) : options_(options) {}

  // A frame's force for the blade at `tip`, taken at `time` (s, the loop's clock) while the
  // device is at `device_tip`.
  void Update(double time, const Eigen::Vector3d& tip, const Eigen::Vector3d& force,
              const Eigen::Vector3d& device_tip);
  // The force to render at `time` with the blade at `tip`.
  Eigen::Vector3d At(double time, const Eigen::Vector3d& tip) const;

  double stiffness() const { return stiffness_; }

 private:
  struct Linear {
    Eigen::Vector3d tip = Eigen::Vector3d::Zero(), force = Eigen::Vector3d::Zero();
    double stiffness = 0;
    Eigen::Vector3d At(const Eigen::Vector3d& x) const { return force - stiffness * (x - tip); }
  };

  Options options_;
  bool started_ = false;
  Linear current_;
  Eigen::Vector3d offset_ = Eigen::Vector3d::Zero();  // rendered - model, at the last update
  double updated_at_ = 0;
  double stiffness_ = 0;
};

}  // namespace kerf::client
