#include "mesh/mesh_quality.h"

#include <gtest/gtest.h>

#include <numeric>

#include "mesh/box_lattice.h"

namespace kerf::mesh {
namespace {

TEST(MeasureMeshQuality, KuhnLatticeTetsAreAllAlike) {
  BoxLatticeSpec spec;
  spec.cells_x = 2;
  spec.cells_y = 2;
  spec.cells_z = 2;
  spec.size = {2, 2, 2};
  const MeshQuality q = MeasureMeshQuality(*MakeBoxLattice(spec));
  // Each Kuhn tet of a unit cube: volume 1/6, dihedral angles 45, 60 and 90 degrees, edges
  // 1, sqrt 2 and sqrt 3.
  EXPECT_EQ(q.tets, 48u);
  EXPECT_NEAR(q.total_volume, 8.0, 1e-12);
  EXPECT_NEAR(q.min_volume, 1.0 / 6, 1e-12);
  EXPECT_NEAR(q.max_volume, 1.0 / 6, 1e-12);
  EXPECT_NEAR(q.min_dihedral_deg, 45.0, 1e-9);
  EXPECT_NEAR(q.max_dihedral_deg, 90.0, 1e-9);
  EXPECT_NEAR(q.min_edge_length, 1.0, 1e-12);
  EXPECT_NEAR(q.max_edge_length, std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(q.min_radius_ratio, q.mean_radius_ratio, 1e-12);
  EXPECT_EQ(q.slivers, 0u);
  EXPECT_EQ(q.min_dihedral_histogram[4], 48u);  // [40, 50)
  EXPECT_EQ(std::accumulate(q.min_dihedral_histogram.begin(), q.min_dihedral_histogram.end(),
                            std::size_t{0}),
            48u);
}

TEST(MeasureMeshQuality, CountsSlivers) {
  TetMesh mesh;
  mesh.AddVertex({0, 0, 0});
  mesh.AddVertex({1, 0, 0});
  mesh.AddVertex({1, 1, 1e-3});
  mesh.AddVertex({0, 1, 0});
  ASSERT_TRUE(mesh.AddTet({VertexId{0}, VertexId{1}, VertexId{2}, VertexId{3}}).ok());
  const MeshQuality q = MeasureMeshQuality(mesh);
  EXPECT_EQ(q.slivers, 1u);
  EXPECT_EQ(q.min_dihedral_histogram[0], 1u);
  EXPECT_EQ(MeasureMeshQuality(mesh, /*sliver_angle_deg=*/0.01).slivers, 0u);
}

TEST(MeasureMeshQuality, EmptyMeshIsAllZero) {
  const MeshQuality q = MeasureMeshQuality(TetMesh());
  EXPECT_EQ(q.tets, 0u);
  EXPECT_EQ(q.min_dihedral_deg, 0.0);
}

}  // namespace
}  // namespace kerf::mesh
