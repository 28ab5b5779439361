#include "mesh/boundary_surface.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "mesh/box_lattice.h"
#include "support/find_vertex.h"

namespace kerf::mesh {
namespace {

TEST(ExtractBoundarySurface, LatticeBoundaryIsTheBoxFacesOrientedOutward) {
  BoxLatticeSpec spec;
  spec.cells_x = 3;
  spec.cells_y = 4;
  spec.cells_z = 2;
  const TetMesh mesh = *MakeBoxLattice(spec);
  const std::vector<BoundaryTriangle> triangles = ExtractBoundarySurface(mesh);
  // Two triangles per boundary square.
  EXPECT_EQ(triangles.size(), 2u * 2 * (3 * 4 + 4 * 2 + 3 * 2));

  // Closed and outward: the area vectors sum to zero and the divergence theorem gives the
  // volume, sum over triangles of (centroid . area vector) / 3.
  Eigen::Vector3d area_sum = Eigen::Vector3d::Zero();
  double volume = 0;
  for (const BoundaryTriangle& tri : triangles) {
    const Eigen::Vector3d& a = mesh.rest_position(tri.vertices[0]);
    const Eigen::Vector3d& b = mesh.rest_position(tri.vertices[1]);
    const Eigen::Vector3d& c = mesh.rest_position(tri.vertices[2]);
    const Eigen::Vector3d area = 0.5 * (b - a).cross(c - a);
    area_sum += area;
    volume += ((a + b + c) / 3).dot(area) / 3;
    // Every vertex on the box's surface.
    for (const VertexId v : tri.vertices) {
      const Eigen::Vector3d& p = mesh.rest_position(v);
      EXPECT_TRUE(p.x() == 0 || p.x() == 3 || p.y() == 0 || p.y() == 4 || p.z() == 0 || p.z() == 2);
    }
    EXPECT_FALSE(TetHasVertex({tri.vertices[0], tri.vertices[1], tri.vertices[2], tri.vertices[2]},
                              mesh.tet(tri.tet)[tri.opposite_corner]));
  }
  EXPECT_NEAR(area_sum.norm(), 0.0, 1e-12);
  EXPECT_NEAR(volume, 24.0, 1e-12);
}

TEST(ExtractBoundarySurface, RemovingATetExposesItsInteriorFaces) {
  BoxLatticeSpec spec;
  spec.cells_x = 3;
  spec.cells_y = 3;
  spec.cells_z = 3;
  TetMesh mesh = *MakeBoxLattice(spec);
  const std::size_t before = ExtractBoundarySurface(mesh).size();
  // A tet of the middle cube has four interior faces, which become boundary.
  const TetId middle = kerf::testing::TetWithCentroidIn(mesh, {1, 1, 1}, {2, 2, 2});
  ASSERT_TRUE(mesh.RemoveTet(middle).ok());
  EXPECT_EQ(ExtractBoundarySurface(mesh).size(), before + 4);
}

}  // namespace
}  // namespace kerf::mesh
