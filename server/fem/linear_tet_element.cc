#include "fem/linear_tet_element.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>

#include "base/check.h"

namespace kerf::fem {

std::array<Eigen::Vector3d, 4> ShapeFunctionGradients(const std::array<Eigen::Vector3d, 4>& x) {
  // Columns are the edges from corner 0; the rows of the inverse are g_1, g_2, g_3.
  Eigen::Matrix3d edges;
  edges << x[1] - x[0], x[2] - x[0], x[3] - x[0];
  KERF_CHECK(edges.determinant() != 0);
  const Eigen::Matrix3d inverse = edges.inverse();
  std::array<Eigen::Vector3d, 4> g;
  for (int a = 1; a < 4; ++a) g[a] = inverse.row(a - 1).transpose();
  g[0] = -(g[1] + g[2] + g[3]);
  return g;
}

LinearTetStiffness ComputeLinearTetStiffness(const std::array<Eigen::Vector3d, 4>& rest,
                                             const LameParameters& lame) {
  LinearTetStiffness k;
  k.gradients = ShapeFunctionGradients(rest);
  const std::array<Eigen::Vector3d, 4>& g = k.gradients;
  k.volume = std::abs((rest[1] - rest[0]).cross(rest[2] - rest[0]).dot(rest[3] - rest[0])) / 6;
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      k.blocks[a][b] =
          k.volume * (lame.lambda * g[a] * g[b].transpose() + lame.mu * g[b] * g[a].transpose() +
                      lame.mu * g[a].dot(g[b]) * Eigen::Matrix3d::Identity());
    }
  }
  return k;
}

}  // namespace kerf::fem
