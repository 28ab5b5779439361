#include "mesh/connected_components.h"

#include <gtest/gtest.h>

#include "mesh/box_lattice.h"

namespace kerf::mesh {
namespace {

TEST(FindConnectedComponents, LatticeIsOnePiece) {
  BoxLatticeSpec spec;
  spec.cells_x = 3;
  const MeshComponents components = FindConnectedComponents(*MakeBoxLattice(spec));
  EXPECT_EQ(components.count, 1u);
  for (const std::int32_t label : components.tet_component) EXPECT_EQ(label, 0);
}

TEST(FindConnectedComponents, RemovingTheMiddleCubeOfABarLeavesTwoPieces) {
  BoxLatticeSpec spec;
  spec.cells_x = 3;
  TetMesh mesh = *MakeBoxLattice(spec);
  // Tets 6..11 fill the middle cube. Cube 0 spans x in [0, 1] and cube 2 spans [2, 3]:
  // without cube 1 they share no vertex.
  for (std::uint32_t t = 6; t < 12; ++t) ASSERT_TRUE(mesh.RemoveTet(TetId{t}).ok());
  const MeshComponents components = FindConnectedComponents(mesh);
  EXPECT_EQ(components.count, 2u);
  EXPECT_EQ(components.tet_component[0], 0);
  EXPECT_EQ(components.tet_component[7], -1);  // dead slot
  EXPECT_EQ(components.tet_component[12], 1);
}

TEST(FindConnectedComponents, TetsSharingOnlyAVertexAreConnected) {
  TetMesh mesh;
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
        Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(0, -1, 0),
        Eigen::Vector3d(0, 0, -1)}) {
    mesh.AddVertex(p);
  }
  ASSERT_TRUE(mesh.AddTet({VertexId{0}, VertexId{1}, VertexId{2}, VertexId{3}}).ok());
  ASSERT_TRUE(mesh.AddTet({VertexId{0}, VertexId{4}, VertexId{5}, VertexId{6}}).ok());
  EXPECT_EQ(FindConnectedComponents(mesh).count, 1u);
}

}  // namespace
}  // namespace kerf::mesh
