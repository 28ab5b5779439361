#include "fem/linear_tet_element.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace kerf::fem {
namespace {

using Eigen::Vector3d;

Eigen::MatrixXd Dense(const LinearTetStiffness& k) {
  Eigen::MatrixXd dense(12, 12);
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) dense.block<3, 3>(3 * a, 3 * b) = k.blocks[a][b];
  }
  return dense;
}

TEST(ComputeLinearTetStiffness, CornerTetPenAndPaper) {
  // Corner tet: g_1 = x, g_2 = y, g_3 = z, g_0 = -(1, 1, 1), V = 1/6. With lambda = 400,
  // mu = 100: K_11 = V (lambda + 2 mu, mu, mu) on the diagonal, K_12 = V (lambda e_x e_y^T +
  // mu e_y e_x^T).
  const LinearTetStiffness k = ComputeLinearTetStiffness(
      {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d(0, 0, 1)}, {400, 100});
  EXPECT_NEAR(k.volume, 1.0 / 6, 1e-15);
  Eigen::Matrix3d k11 = Eigen::Vector3d(600, 100, 100).asDiagonal();
  EXPECT_TRUE(k.blocks[1][1].isApprox(k11 / 6, 1e-14)) << k.blocks[1][1];
  Eigen::Matrix3d k12 = Eigen::Matrix3d::Zero();
  k12(0, 1) = 400.0 / 6;
  k12(1, 0) = 100.0 / 6;
  EXPECT_TRUE(k.blocks[1][2].isApprox(k12, 1e-14)) << k.blocks[1][2];
}

TEST(ComputeLinearTetStiffness, SymmetricWithTranslationsAndRotationsInTheNullSpace) {
  const std::array<Vector3d, 4> x = {Vector3d(0.1, 0.2, 0.0), Vector3d(1.3, 0.1, 0.2),
                                     Vector3d(0.4, 1.1, -0.1), Vector3d(0.2, 0.5, 0.9)};
  const Eigen::MatrixXd k = Dense(ComputeLinearTetStiffness(x, {1000, 300}));
  EXPECT_TRUE(k.isApprox(k.transpose(), 1e-14));
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::VectorXd translation = Eigen::VectorXd::Zero(12);
    Eigen::VectorXd rotation(12);
    for (int a = 0; a < 4; ++a) {
      translation[3 * a + axis] = 1;
      rotation.segment<3>(3 * a) = Vector3d::Unit(axis).cross(x[a]);  // infinitesimal rotation
    }
    EXPECT_LT((k * translation).norm(), 1e-10 * k.norm());
    EXPECT_LT((k * rotation).norm(), 1e-10 * k.norm());
  }
  // Positive semi-definite with exactly six zero eigenvalues (rigid motions).
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(k);
  int zero = 0;
  for (int i = 0; i < 12; ++i) {
    EXPECT_GT(eigen.eigenvalues()[i], -1e-9 * k.norm());
    if (std::abs(eigen.eigenvalues()[i]) < 1e-9 * k.norm()) ++zero;
  }
  EXPECT_EQ(zero, 6);
}

TEST(ComputeLinearTetStiffness, UniformStrainEnergyMatchesContinuum) {
  // u = E x for a symmetric strain E: energy V (lambda tr(E)^2 / 2 + mu E:E).
  const std::array<Vector3d, 4> x = {Vector3d(0, 0, 0), Vector3d(2, 0, 0), Vector3d(0, 1, 0),
                                     Vector3d(0.3, 0.2, 1.5)};
  const double lambda = 700, mu = 250;
  Eigen::Matrix3d strain;
  strain << 0.01, 0.002, -0.003, 0.002, -0.004, 0.005, -0.003, 0.005, 0.02;
  const LinearTetStiffness k = ComputeLinearTetStiffness(x, {lambda, mu});
  Eigen::VectorXd u(12);
  for (int a = 0; a < 4; ++a) u.segment<3>(3 * a) = strain * x[a];
  const double energy = 0.5 * u.dot(Dense(k) * u);
  const double expected =
      k.volume * (lambda * strain.trace() * strain.trace() / 2 + mu * strain.squaredNorm());
  EXPECT_NEAR(energy, expected, 1e-12 * expected);
}

}  // namespace
}  // namespace kerf::fem
