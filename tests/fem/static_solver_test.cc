#include "fem/static_solver.h"

#include <gtest/gtest.h>

#include "mesh/box_lattice.h"
#include "support/find_vertex.h"
#include "support/status_message.h"

namespace kerf::fem {
namespace {

using kerf::testing::StatusMessage;
using mesh::VertexId;

mesh::TetMesh Bar(int n, double length = 5) {
  mesh::BoxLatticeSpec spec;
  spec.cells_x = 5 * n;
  spec.cells_y = n;
  spec.cells_z = n;
  spec.size = {length, 1, 1};
  return *mesh::MakeBoxLattice(spec);
}

Material AccuracyBarMaterial() {  // ../shared/design/accuracy.md
  Material m;
  m.youngs_modulus = 5000;
  m.poisson_ratio = 0.45;
  m.density = 1;
  return m;
}

bool OnBoundary(const Eigen::Vector3d& p) {
  return p.x() == 0 || p.x() == 5 || p.y() == 0 || p.y() == 1 || p.z() == 0 || p.z() == 1;
}

TEST(SolveStaticEquilibrium, PatchTestReproducesALinearFieldInside) {
  const mesh::TetMesh m = Bar(2);
  const TensorMassModel model = *TensorMassModel::Create(m, AccuracyBarMaterial());
  Eigen::Matrix3d a;
  a << 0.01, 0.003, -0.002, 0.001, -0.004, 0.002, 0.0, 0.005, 0.007;
  const Eigen::Vector3d b(0.1, -0.2, 0.05);
  BoundaryConditions bc;
  int interior = 0;
  for (const VertexId v : m.vertices()) {
    const Eigen::Vector3d& p = m.rest_position(v);
    if (!OnBoundary(p)) {
      ++interior;
      continue;
    }
    const Eigen::Vector3d u = a * p + b;
    for (int c = 0; c < 3; ++c) bc.prescribed.push_back({v, c, u[c]});
  }
  ASSERT_GT(interior, 0);
  const std::vector<Eigen::Vector3d> u = *SolveStaticEquilibrium(model, bc);
  for (const VertexId v : m.vertices()) {
    const Eigen::Vector3d expected = a * m.rest_position(v) + b;
    EXPECT_LT((u[mesh::Index(v)] - expected).norm(), 1e-12) << mesh::Index(v);
  }
}

TEST(SolveStaticEquilibrium, CantileverUnderGravityBendsDownAsTheReference) {
  // accuracy.md: n = 2, rho g = 1 downward, the tip-face centre moves down 0.06057 (ccx, C3D4,
  // printed to 4 significant digits). The box lattice is the same six-tet split, so the
  // figure is reproduced; every node is compared with ccx in kerf_static_calculix_test.
  const mesh::TetMesh m = Bar(2);
  const TensorMassModel model = *TensorMassModel::Create(m, AccuracyBarMaterial());
  BoundaryConditions bc;
  bc.gravity = {0, 0, -1};
  std::vector<VertexId> clamped;
  for (const VertexId v : m.vertices()) {
    if (m.rest_position(v).x() == 0) clamped.push_back(v);
  }
  FixVertices(clamped, &bc);
  const std::vector<Eigen::Vector3d> u = *SolveStaticEquilibrium(model, bc);
  const VertexId tip_centre = kerf::testing::VertexAt(m, {5, 0.5, 0.5});
  EXPECT_NEAR(-u[mesh::Index(tip_centre)].z(), 0.06057, 0.000005);
}

TEST(SolveStaticEquilibrium, RefusesAFreeBodyAndBadConditions) {
  const mesh::TetMesh m = Bar(1);
  const TensorMassModel model = *TensorMassModel::Create(m, AccuracyBarMaterial());
  BoundaryConditions bc;
  bc.gravity = {0, 0, -1};
  EXPECT_EQ(StatusMessage(SolveStaticEquilibrium(model, bc)),
            "the stiffness is singular: the body can move rigidly; hold it with prescribed "
            "displacements");
  bc.prescribed.push_back({VertexId{999}, 0, 0.0});
  EXPECT_EQ(StatusMessage(SolveStaticEquilibrium(model, bc)),
            "prescribed displacement 0: vertex 999 is not alive");
  bc.prescribed = {{VertexId{0}, 3, 0.0}};
  EXPECT_EQ(StatusMessage(SolveStaticEquilibrium(model, bc)),
            "prescribed displacement 0: component 3 value 0 (need 0..2 and finite)");
}

}  // namespace
}  // namespace kerf::fem
