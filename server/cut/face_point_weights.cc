#include "cut/face_point_weights.h"

#include <algorithm>

namespace kerf::cut {
namespace {

// `w` with its weight `k` raised to `floor`, the other two scaled so that the sum stays 1.
void Raise(Eigen::Vector3d* w, int k, double floor) {
  const double rest = 1 - (*w)[k];  // over 1 - floor > 0: (*w)[k] < floor <= 1/3
  for (int j = 0; j < 3; ++j) {
    if (j != k) (*w)[j] *= (1 - floor) / rest;
  }
  (*w)[k] = floor;
}

}  // namespace

Eigen::Vector3d FacePointOffEdges(const Eigen::Vector3d& b, double share) {
  share = std::clamp(share, 0.0, 1.0 / 3);
  Eigen::Vector3d w = b;
  int smallest = 0;
  w.minCoeff(&smallest);
  if (w[smallest] < share) Raise(&w, smallest, share);
  for (int k = 0; k < 3; ++k) {
    if (w[k] < share / 2) Raise(&w, k, share / 2);
  }
  return w;
}

}  // namespace kerf::cut
