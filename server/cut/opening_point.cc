#include "cut/opening_point.h"

#include <algorithm>

#include "geometry/tet_measures.h"

namespace kerf::cut {

double SmallestFanAngleDeg(const std::array<Eigen::Vector3d, 3>& face, const Eigen::Vector3d& point,
                           std::span<const Eigen::Vector3d> apexes) {
  double smallest = 180;
  for (const Eigen::Vector3d& apex : apexes) {
    for (int k = 0; k < 3; ++k) {
      smallest = std::min(smallest,
                          geometry::SmallestDihedralDeg(apex, point, face[k], face[(k + 1) % 3]));
    }
  }
  return smallest;
}

Eigen::Vector3d OpeningPointWeights(const std::array<Eigen::Vector3d, 3>& face,
                                    std::span<const Eigen::Vector3d> apexes) {
  std::array<Eigen::Vector3d, 7> candidates;
  candidates[0] = Eigen::Vector3d::Constant(1.0 / 3);
  for (int k = 0; k < 3; ++k) {
    candidates[1 + 2 * k] = Eigen::Vector3d::Constant(0.25);  // towards corner k
    candidates[1 + 2 * k][k] = 0.5;
    candidates[2 + 2 * k] = Eigen::Vector3d::Constant(0.4);  // away from corner k
    candidates[2 + 2 * k][k] = 0.2;
  }
  Eigen::Vector3d best = candidates[0];
  double best_angle = -1;
  for (const Eigen::Vector3d& w : candidates) {
    const Eigen::Vector3d point = w[0] * face[0] + w[1] * face[1] + w[2] * face[2];
    const double angle = SmallestFanAngleDeg(face, point, apexes);
    if (angle > best_angle + 1e-9) {
      best_angle = angle;
      best = w;
    }
  }
  return best;
}

}  // namespace kerf::cut
