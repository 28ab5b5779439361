// Writing a mesh and reading it back gives the same mesh, exactly.
#include <gtest/gtest.h>

#include "absl/strings/match.h"
#include "mesh/box_lattice.h"
#include "mesh/io/gmsh_msh_reader.h"
#include "mesh/io/gmsh_msh_writer.h"
#include "mesh/io/mesh_file.h"
#include "mesh/io/vtu_reader.h"
#include "mesh/io/vtu_writer.h"
#include "support/shared_meshes.h"

namespace kerf::mesh {
namespace {

// A lattice with awkward coordinates and a few tets and a vertex removed, so the live ids
// are not contiguous.
TetMesh AwkwardMesh() {
  BoxLatticeSpec spec;
  spec.cells_x = 3;
  spec.cells_y = 2;
  spec.cells_z = 2;
  spec.size = {0.1, 1.0 / 3.0, 2e-7};
  TetMesh mesh = *MakeBoxLattice(spec);
  for (const std::uint32_t t : {0u, 1u, 2u, 3u, 4u, 5u, 40u}) {
    EXPECT_TRUE(mesh.RemoveTet(TetId{t}).ok());
  }
  EXPECT_TRUE(mesh.RemoveVertex(VertexId{0}).ok());  // only cube 0 used it
  return mesh;
}

TEST(RoundTrip, MshKeepsRestPositionsExactlyAndIdsAsTags) {
  const TetMesh mesh = AwkwardMesh();
  absl::StatusOr<TetMeshData> back = ParseGmshMsh(FormatGmshMsh4(mesh), "rt.msh");
  ASSERT_TRUE(back.ok()) << back.status();
  const TetMeshData expected = ExtractTetMeshData(mesh);
  EXPECT_EQ(back->points, expected.points);
  EXPECT_EQ(back->tets, expected.tets);
  ASSERT_EQ(back->point_ids.size(), expected.point_ids.size());
  for (std::size_t i = 0; i < expected.point_ids.size(); ++i) {
    EXPECT_EQ(back->point_ids[i], expected.point_ids[i] + 1);
  }
}

TEST(RoundTrip, VtuKeepsCurrentPositionsExactly) {
  TetMesh mesh = AwkwardMesh();
  for (const VertexId v : mesh.vertices()) {
    mesh.set_current_position(v, mesh.rest_position(v) * 1.1 + Eigen::Vector3d(0, 0, 1e-9));
  }
  absl::StatusOr<TetMeshData> back = ParseVtu(FormatVtu(mesh), "rt.vtu");
  ASSERT_TRUE(back.ok()) << back.status();
  const TetMeshData expected = ExtractTetMeshData(mesh, /*current=*/true);
  EXPECT_EQ(back->points, expected.points);
  EXPECT_EQ(back->tets, expected.tets);
}

TEST(RoundTrip, VtuCarriesExtraPointAndCellArrays) {
  const TetMesh mesh = AwkwardMesh();
  VtuExtraArrays extra;
  extra.point_data.push_back(
      {"source_vertex", 1, std::vector<std::int64_t>(mesh.vertex_count(), -1)});
  extra.cell_data.push_back({"quality", 1, std::vector<double>(mesh.tet_count(), 0.5)});
  const std::string text = FormatVtu(mesh, extra);
  EXPECT_TRUE(absl::StrContains(text, "Name=\"source_vertex\""));
  EXPECT_TRUE(absl::StrContains(text, "Name=\"quality\""));
  EXPECT_TRUE(ParseVtu(text, "extra.vtu").ok());
}

TEST(RoundTrip, FilesThroughEveryWrittenFormat) {
  const std::string directory = ::testing::TempDir();
  const TetMesh mesh = AwkwardMesh();
  for (const char* name : {"rt.msh", "rt.vtu"}) {
    const std::string path = directory + "/" + name;
    ASSERT_TRUE(WriteMeshFile(mesh, path).ok());
    absl::StatusOr<TetMesh> back = ReadMeshFile(path);
    ASSERT_TRUE(back.ok()) << back.status();
    EXPECT_EQ(back->tet_count(), mesh.tet_count());
    EXPECT_EQ(back->vertex_count(), mesh.vertex_count());
  }
}

TEST(RoundTrip, SharedLiverThroughMshAndVtu) {
  const std::string path = kerf::testing::SharedMeshPath("liver2.msh");
  if (path.empty()) GTEST_SKIP() << "shared/meshes is not beside the repo";
  const TetMesh mesh = *ReadMeshFile(path);
  const TetMeshData expected = ExtractTetMeshData(mesh);
  for (const bool msh : {true, false}) {
    absl::StatusOr<TetMeshData> back =
        msh ? ParseGmshMsh(FormatGmshMsh4(mesh), "l.msh") : ParseVtu(FormatVtu(mesh), "l.vtu");
    ASSERT_TRUE(back.ok()) << back.status();
    EXPECT_EQ(back->points, expected.points);
    EXPECT_EQ(back->tets, expected.tets);
  }
}

}  // namespace
}  // namespace kerf::mesh
