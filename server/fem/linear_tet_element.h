// The linear (4-node) tetrahedral element of isotropic linear elasticity.
#pragma once

#include <Eigen/Core>
#include <array>

#include "fem/material.h"

namespace kerf::fem {

// The element stiffness K^e = V B^T D B as its 4 x 4 blocks of 3 x 3: block (a, b) maps the
// displacement of corner b to the force on corner a,
//   K_ab = V (lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I),
// with g_a the (constant) gradient of corner a's shape function on the rest shape. Blocks
// satisfy K_ba = K_ab^T and every block row sums to zero (rigid translations cost nothing).
// The rest tet must have non-zero volume (asserted); its orientation does not matter.
struct LinearTetStiffness {
  std::array<std::array<Eigen::Matrix3d, 4>, 4> blocks;
  double volume;                             // |V| of the rest shape
  std::array<Eigen::Vector3d, 4> gradients;  // g_0..g_3
};

LinearTetStiffness ComputeLinearTetStiffness(const std::array<Eigen::Vector3d, 4>& rest,
                                             const LameParameters& lame);

// The shape function gradients g_0..g_3 on the rest shape (they sum to zero).
std::array<Eigen::Vector3d, 4> ShapeFunctionGradients(const std::array<Eigen::Vector3d, 4>& rest);

}  // namespace kerf::fem
