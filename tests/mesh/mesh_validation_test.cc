#include "mesh/mesh_validation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mesh/box_lattice.h"
#include "support/status_message.h"

namespace kerf::mesh {
namespace {

using ::testing::ElementsAre;
using ::testing::SizeIs;

// Vertices 0..3 of the unit corner tet and 4 = (1, 1, 1), no tets.
TetMesh FiveVertices() {
  TetMesh mesh;
  mesh.AddVertex({0, 0, 0});
  mesh.AddVertex({1, 0, 0});
  mesh.AddVertex({0, 1, 0});
  mesh.AddVertex({0, 0, 1});
  mesh.AddVertex({1, 1, 1});
  return mesh;
}

TetVertices Tet(int a, int b, int c, int d) {
  return {VertexId(a), VertexId(b), VertexId(c), VertexId(d)};
}

TEST(FindMeshDefects, LatticeIsValid) {
  BoxLatticeSpec spec;
  spec.cells_x = 3;
  spec.cells_y = 2;
  spec.cells_z = 2;
  const TetMesh mesh = *MakeBoxLattice(spec);
  EXPECT_THAT(FindMeshDefects(mesh), SizeIs(0));
  EXPECT_TRUE(ValidateMesh(mesh).ok());
}

TEST(FindMeshDefects, InvertedTetHasNonPositiveVolume) {
  TetMesh mesh = FiveVertices();
  ASSERT_TRUE(mesh.AddTet(Tet(0, 2, 1, 3)).ok());
  ASSERT_TRUE(mesh.AddTet(Tet(1, 2, 3, 4)).ok());  // positive, shares face 1-2-3
  const std::vector<MeshDefect> defects = FindMeshDefects(mesh);
  ASSERT_THAT(defects, SizeIs(1));
  EXPECT_EQ(defects[0].kind, MeshDefectKind::kNonPositiveVolume);
  EXPECT_THAT(defects[0].tets, ElementsAre(TetId{0}));
  EXPECT_DOUBLE_EQ(defects[0].rest_volume, -1.0 / 6);
  EXPECT_EQ(defects[0].message, "tet 0 has non-positive rest volume -0.166667");
}

TEST(FindMeshDefects, FlatTetHasNonPositiveVolume) {
  TetMesh mesh = FiveVertices();
  const VertexId in_plane = mesh.AddVertex({0.5, 0.5, 0});
  ASSERT_TRUE(mesh.AddTet({VertexId{0}, VertexId{1}, VertexId{2}, in_plane}).ok());
  const std::vector<MeshDefect> defects = FindMeshDefects(mesh);
  ASSERT_FALSE(defects.empty());
  EXPECT_EQ(defects[0].kind, MeshDefectKind::kNonPositiveVolume);
  EXPECT_EQ(defects[0].rest_volume, 0.0);
}

TEST(FindMeshDefects, RepeatedVertex) {
  TetMesh mesh = FiveVertices();
  ASSERT_TRUE(mesh.AddTet(Tet(0, 1, 2, 3)).ok());
  ASSERT_TRUE(mesh.AddTet(Tet(1, 2, 4, 2)).ok());
  const std::vector<MeshDefect> defects = FindMeshDefects(mesh);
  ASSERT_THAT(defects, SizeIs(1));
  EXPECT_EQ(defects[0].kind, MeshDefectKind::kRepeatedVertex);
  EXPECT_THAT(defects[0].tets, ElementsAre(TetId{1}));
  EXPECT_EQ(defects[0].message, "tet 1 repeats a vertex: (1, 2, 4, 2)");
}

TEST(FindMeshDefects, FaceInThreeTetsIsReportedOnce) {
  TetMesh mesh = FiveVertices();
  const VertexId below = mesh.AddVertex({0.2, 0.2, -1});
  const VertexId above2 = mesh.AddVertex({0.1, 0.1, 2});
  ASSERT_TRUE(mesh.AddTet(Tet(0, 1, 2, 3)).ok());
  ASSERT_TRUE(mesh.AddTet({VertexId{0}, VertexId{2}, VertexId{1}, below}).ok());
  ASSERT_TRUE(mesh.AddTet({VertexId{0}, VertexId{1}, VertexId{2}, above2}).ok());
  ASSERT_TRUE(mesh.AddTet(Tet(1, 2, 3, 4)).ok());  // dangling-free: uses vertex 4
  const std::vector<MeshDefect> defects = FindMeshDefects(mesh);
  ASSERT_THAT(defects, SizeIs(1));
  EXPECT_EQ(defects[0].kind, MeshDefectKind::kOverSharedFace);
  EXPECT_THAT(defects[0].tets, ElementsAre(TetId{0}, TetId{1}, TetId{2}));
  EXPECT_THAT(defects[0].vertices, ElementsAre(VertexId{0}, VertexId{1}, VertexId{2}));
  EXPECT_EQ(defects[0].message, "face (0, 1, 2) is shared by 3 tets: 0, 1, 2");
}

TEST(FindMeshDefects, DanglingVertex) {
  TetMesh mesh = FiveVertices();
  ASSERT_TRUE(mesh.AddTet(Tet(0, 1, 2, 3)).ok());
  const std::vector<MeshDefect> defects = FindMeshDefects(mesh);
  ASSERT_THAT(defects, SizeIs(1));
  EXPECT_EQ(defects[0].kind, MeshDefectKind::kDanglingVertex);
  EXPECT_THAT(defects[0].vertices, ElementsAre(VertexId{4}));
  EXPECT_EQ(defects[0].message, "vertex 4 is used by no tet");
}

TEST(ValidateMesh, SummarisesDefects) {
  TetMesh mesh = FiveVertices();
  ASSERT_TRUE(mesh.AddTet(Tet(0, 2, 1, 3)).ok());
  const absl::Status status = ValidateMesh(mesh);
  EXPECT_EQ(status.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_EQ(kerf::testing::StatusMessage(status),
            "mesh has 2 defect(s): tet 0 has non-positive rest volume -0.166667; vertex 4 is "
            "used by no tet");
}

}  // namespace
}  // namespace kerf::mesh
