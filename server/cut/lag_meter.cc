#include "cut/lag_meter.h"

#include <algorithm>

namespace kerf::cut {
namespace {

using Polygon = std::vector<Eigen::Vector3d>;

// The part of the polygon on the side of the plane (through `p` with normal `n`) where
// (x - p) . n >= 0.
Polygon ClipByPlane(const Polygon& polygon, const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
  Polygon out;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector3d& a = polygon[i];
    const Eigen::Vector3d& b = polygon[(i + 1) % polygon.size()];
    const double da = (a - p).dot(n), db = (b - p).dot(n);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

double PolygonArea(const Polygon& polygon) {
  Eigen::Vector3d twice = Eigen::Vector3d::Zero();
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    twice += (polygon[i] - polygon[0]).cross(polygon[i + 1] - polygon[0]);
  }
  return 0.5 * twice.norm();
}

}  // namespace

LagMeter::LagMeter(const mesh::TetMesh& tissue) {
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
  for (const mesh::TetId t : tissue.tets()) {
    std::array<Eigen::Vector3d, 4> x;
    for (int k = 0; k < 4; ++k) x[k] = tissue.current_position(tissue.tet(t)[k]);
    tets_.push_back(x);
    boxes_.push_back({x[0].cwiseMin(x[1]).cwiseMin(x[2]).cwiseMin(x[3]),
                      x[0].cwiseMax(x[1]).cwiseMax(x[2]).cwiseMax(x[3])});
    low = low.cwiseMin(boxes_.back()[0]);
    high = high.cwiseMax(boxes_.back()[1]);
  }
  tolerance_ = 1e-9 * (high - low).squaredNorm();
}

double LagMeter::AreaInside(const std::array<Eigen::Vector3d, 3>& triangle) const {
  const Eigen::Vector3d low = triangle[0].cwiseMin(triangle[1]).cwiseMin(triangle[2]);
  const Eigen::Vector3d high = triangle[0].cwiseMax(triangle[1]).cwiseMax(triangle[2]);
  double area = 0;
  for (std::size_t t = 0; t < tets_.size(); ++t) {
    if ((boxes_[t][0].array() > high.array()).any() || (boxes_[t][1].array() < low.array()).any()) {
      continue;
    }
    const std::array<Eigen::Vector3d, 4>& x = tets_[t];
    Polygon polygon(triangle.begin(), triangle.end());
    for (const auto& f : mesh::kTetFaces) {
      const int opposite = 6 - f[0] - f[1] - f[2];
      Eigen::Vector3d n = (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]]);
      if ((x[opposite] - x[f[0]]).dot(n) < 0) n = -n;
      polygon = ClipByPlane(polygon, x[f[0]], n);
      if (polygon.size() < 3) break;
    }
    if (polygon.size() >= 3) area += PolygonArea(polygon);
  }
  return area;
}

PoseLag LagMeter::Measure(const BladePose& pose, double open_area) {
  double swept = swept_.empty() ? 0 : swept_.back();
  double travel = travel_.empty() ? 0 : travel_.back();
  if (previous_) {
    swept += AreaInside({previous_->tip, previous_->heel, pose.heel});
    swept += AreaInside({previous_->tip, pose.heel, pose.tip});
    travel += (pose.tip - previous_->tip).norm();
  }
  previous_ = pose;
  swept_.push_back(swept);
  travel_.push_back(travel);
  PoseLag lag;
  lag.swept_area = swept;
  lag.open_area = open_area;
  lag.lag_area = std::max(0.0, swept - lag.open_area);
  // The last pose whose swept surface is all open (swept areas only grow), up to a quarter of
  // the largest step: the crack is flat in each tet, the swept surface of a turning blade is not.
  if (swept_.size() > 1) {
    largest_step_ = std::max(largest_step_, swept_.back() - swept_[swept_.size() - 2]);
  }
  const double open = lag.open_area + 0.25 * largest_step_ + tolerance_;
  std::size_t p = swept_.size() - 1;
  while (p > 0 && swept_[p] > open) --p;
  lag.lag_steps = static_cast<int>(swept_.size() - 1 - p);
  lag.lag_distance = travel - travel_[p];
  return lag;
}

}  // namespace kerf::cut
