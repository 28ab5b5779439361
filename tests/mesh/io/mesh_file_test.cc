#include "mesh/io/mesh_file.h"

#include <gtest/gtest.h>

#include "mesh/box_lattice.h"
#include "support/status_message.h"

namespace kerf::mesh {
namespace {

TEST(MeshFile, ReadsTetGenPairFromEitherName) {
  const std::string base = ::testing::TempDir() + "/pair";
  ASSERT_TRUE(WriteTextFile(base + ".node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n").ok());
  ASSERT_TRUE(WriteTextFile(base + ".ele", "1 4 0\n1 1 2 3 4\n").ok());
  for (const char* extension : {".node", ".ele"}) {
    absl::StatusOr<TetMesh> mesh = ReadMeshFile(base + extension);
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    EXPECT_EQ(mesh->tet_count(), 1u);
  }
}

TEST(MeshFile, ClearErrors) {
  EXPECT_EQ(kerf::testing::StatusMessage(ReadMeshFile("/no/such/mesh.msh")),
            "/no/such/mesh.msh: cannot open file");
  EXPECT_EQ(kerf::testing::StatusMessage(ReadMeshFile("mesh.stl")),
            "mesh.stl: unknown mesh format '.stl'; kerf reads .msh, .vtk, .vtu, .node/.ele and "
            ".inp");
  EXPECT_EQ(ReadMeshFile(::testing::TempDir()).status().code(), absl::StatusCode::kInvalidArgument);
  BoxLatticeSpec spec;
  EXPECT_EQ(WriteMeshFile(*MakeBoxLattice(spec), "out.vtk").message(),
            "out.vtk: cannot write '.vtk'; kerf writes .vtu and .msh");
  EXPECT_EQ(WriteMeshFile(*MakeBoxLattice(spec), "/no/such/dir/out.vtu").code(),
            absl::StatusCode::kPermissionDenied);
}

}  // namespace
}  // namespace kerf::mesh
