#include "cut/tissue_surface.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "mesh/box_lattice.h"

namespace kerf::cut {
namespace {

// A 2x2x2 lattice of unit cubes: its middle vertex (1, 1, 1) is the only one inside.
class TissueSurfaceTest : public ::testing::Test {
 protected:
  mesh::VertexId At(const Eigen::Vector3d& x) const {
    for (const mesh::VertexId v : lattice_.vertices()) {
      if ((lattice_.rest_position(v) - x).norm() < 1e-12) return v;
    }
    ADD_FAILURE() << "no vertex at " << x.transpose();
    return mesh::VertexId(0);
  }

  mesh::TetMesh lattice_ = *mesh::MakeBoxLattice({.cells_x = 2, .cells_y = 2, .cells_z = 2});
  TissueSurface surface_ = TissueSurface::Of(lattice_);
};

TEST_F(TissueSurfaceTest, HoldsTheBoundaryAndNothingInside) {
  const mesh::VertexId middle = At({1, 1, 1}), top = At({1, 1, 2}), corner = At({0, 0, 0});
  EXPECT_FALSE(surface_.HasVertex(middle));
  EXPECT_TRUE(surface_.HasVertex(top));
  EXPECT_TRUE(surface_.HasVertex(corner));
  EXPECT_FALSE(surface_.HasEdge(middle, top));  // through the inside
  EXPECT_TRUE(surface_.HasEdge(top, At({0, 1, 2})));
  EXPECT_FALSE(surface_.HasEdge(top, At({0, 0, 0})));  // not an edge at all
  int boundary_faces = 0;
  for (const mesh::TetId t : lattice_.tets()) {
    const mesh::TetVertices& v = lattice_.tet(t);
    for (const auto& f : mesh::kTetFaces) {
      boundary_faces += surface_.HasFace(MakeFaceKey(v[f[0]], v[f[1]], v[f[2]]));
    }
  }
  EXPECT_EQ(boundary_faces, 6 * 4 * 2);  // two triangles for each of the 24 squares
}

TEST_F(TissueSurfaceTest, TrianglesAtAVertexAreTheSurfacesAroundIt) {
  EXPECT_TRUE(surface_.TrianglesAt(At({1, 1, 1})).empty());
  // The top's middle: as many as the boundary faces of the lattice's tets at it.
  const mesh::VertexId top = At({1, 1, 2});
  std::size_t faces_at_top = 0;
  for (const mesh::TetId t : lattice_.tets()) {
    const mesh::TetVertices& v = lattice_.tet(t);
    for (const auto& f : mesh::kTetFaces) {
      const FaceKey key = MakeFaceKey(v[f[0]], v[f[1]], v[f[2]]);
      faces_at_top += surface_.HasFace(key) && std::find(key.begin(), key.end(), top) != key.end();
    }
  }
  const auto around = surface_.TrianglesAt(top);
  EXPECT_GE(around.size(), 4u);
  EXPECT_EQ(around.size(), faces_at_top);
  for (const auto& t : around) {
    EXPECT_NE(std::find(t.begin(), t.end(), top), t.end());
    EXPECT_TRUE(surface_.HasFace(MakeFaceKey(t[0], t[1], t[2])));
    for (const mesh::VertexId v : t) EXPECT_EQ(lattice_.rest_position(v).z(), 2);
  }
}

TEST_F(TissueSurfaceTest, TheNormalPointsOutOnCurrentPositions) {
  EXPECT_TRUE(surface_.Normal(lattice_, At({1, 1, 2})).isApprox(Eigen::Vector3d(0, 0, 1)));
  EXPECT_TRUE(surface_.Normal(lattice_, At({1, 0, 1})).isApprox(Eigen::Vector3d(0, -1, 0)));
  EXPECT_EQ(surface_.Normal(lattice_, At({1, 1, 1})), Eigen::Vector3d::Zero());
  // At a corner of the box, between the three faces there.
  const Eigen::Vector3d corner = surface_.Normal(lattice_, At({2, 2, 2}));
  EXPECT_GT(corner.minCoeff(), 0);
  EXPECT_NEAR(corner.norm(), 1, 1e-12);
  // Turned with the tissue: the top's normal turns too.
  mesh::TetMesh turned = lattice_;
  for (const mesh::VertexId v : turned.vertices()) {
    const Eigen::Vector3d& x = turned.rest_position(v);
    ASSERT_TRUE(turned.MoveVertex(v, x, Eigen::Vector3d(x.x(), -x.z(), x.y())).ok());
  }
  EXPECT_TRUE(surface_.Normal(turned, At({1, 1, 2})).isApprox(Eigen::Vector3d(0, -1, 0)));
}

// A segment lies on the surface at an edge where it is in the plane of a surface triangle at that
// edge: a segment on the top at the top's edge does, the same segment lifted past the tolerance,
// or standing up through the top, does not, nor does one at an edge inside.
TEST_F(TissueSurfaceTest, ASegmentInTheTopsPlaneLiesOnTheTopAtItsEdges) {
  const mesh::VertexId a = At({1, 1, 2}), b = At({0, 1, 2});
  ASSERT_TRUE(surface_.HasEdge(a, b));
  const Eigen::Vector3d p(0.5, -1, 2), q(0.5, 3, 2);
  EXPECT_TRUE(surface_.SegmentOnFaceAtEdge(lattice_, a, b, p, q, 1e-3));
  const Eigen::Vector3d up(0, 0, 2e-3);
  EXPECT_FALSE(surface_.SegmentOnFaceAtEdge(lattice_, a, b, p + up, q + up, 1e-3));
  EXPECT_TRUE(surface_.SegmentOnFaceAtEdge(lattice_, a, b, p + up, q + up, 3e-3));
  EXPECT_FALSE(surface_.SegmentOnFaceAtEdge(lattice_, a, b, {0.5, 1, 1}, {0.5, 1, 3}, 1e-3));
  EXPECT_FALSE(surface_.SegmentOnFaceAtEdge(lattice_, At({1, 1, 1}), a, p, q, 1e-3));
}

}  // namespace
}  // namespace kerf::cut
