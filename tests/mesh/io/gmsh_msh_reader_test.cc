#include "mesh/io/gmsh_msh_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mesh/io/mesh_file.h"
#include "mesh/mesh_validation.h"
#include "support/shared_meshes.h"
#include "support/status_message.h"

namespace kerf::mesh {
namespace {

using ::testing::ElementsAre;

// Two tets sharing face (2, 3, 4), node ids not contiguous, plus a triangle and a line.
constexpr char kVersion1[] = R"($NOD
5
1 0 0 0
2 1 0 0
3 0 1 0
4 0 0 1
9 1 1 1
$ENDNOD
$ELM
4
1 1 0 0 2 1 2
2 2 0 0 3 1 2 3
3 4 1 1 4 1 2 3 4
4 4 1 1 4 2 3 4 9
$ENDELM
)";

constexpr char kVersion2[] = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
1
3 1 "liver"
$EndPhysicalNames
$Nodes
5
1 0 0 0
2 1 0 0
3 0 1 0
4 0 0 1
9 1 1 1
$EndNodes
$Elements
3
1 2 2 0 1 1 2 3
2 4 2 1 1 1 2 3 4
3 4 2 1 1 2 3 4 9
$EndElements
)";

constexpr char kVersion41[] = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Entities
0 0 0 1
1 0 0 0 1 1 1 0 0
$EndEntities
$Nodes
1 5 1 9
3 1 0 5
1
2
3
4
9
0 0 0
1 0 0
0 1 0
0 0 1
1 1 1
$EndNodes
$Elements
2 3 1 3
2 1 2 1
1 1 2 3
3 1 4 2
2 1 2 3 4
3 2 3 4 9
$EndElements
)";

constexpr char kVersion40[] = R"($MeshFormat
4 0 8
$EndMeshFormat
$Nodes
1 5
1 3 0 5
1 0 0 0
2 1 0 0
3 0 1 0
4 0 0 1
9 1 1 1
$EndNodes
$Elements
1 2
1 3 4 2
1 1 2 3 4
2 2 3 4 9
$EndElements
)";

void ExpectTheTwoMshTets(const absl::StatusOr<TetMeshData>& data) {
  ASSERT_TRUE(data.ok()) << data.status();
  EXPECT_THAT(data->point_ids, ElementsAre(1, 2, 3, 4, 9));
  EXPECT_EQ(data->points[4], Eigen::Vector3d(1, 1, 1));
  ASSERT_EQ(data->tets.size(), 2u);
  EXPECT_THAT(data->tets[0], ElementsAre(0, 1, 2, 3));
  EXPECT_THAT(data->tets[1], ElementsAre(1, 2, 3, 4));
}

TEST(ParseGmshMsh, Version1) { ExpectTheTwoMshTets(ParseGmshMsh(kVersion1, "v1.msh")); }
TEST(ParseGmshMsh, Version2) { ExpectTheTwoMshTets(ParseGmshMsh(kVersion2, "v2.msh")); }
TEST(ParseGmshMsh, Version41) { ExpectTheTwoMshTets(ParseGmshMsh(kVersion41, "v41.msh")); }
TEST(ParseGmshMsh, Version40) { ExpectTheTwoMshTets(ParseGmshMsh(kVersion40, "v40.msh")); }

struct BadCase {
  const char* text;
  const char* message;
};

TEST(ParseGmshMsh, ErrorsNameFileLineAndExpectation) {
  const BadCase cases[] = {
      {"", "bad.msh:1: expected '$MeshFormat' (MSH 2 or 4) or '$NOD' (MSH 1), found end of file"},
      {"$NOD\n2\n1 0 0 0\n2 0 x 0\n$ENDNOD\n",
       "bad.msh:4: expected coordinate y (a finite number), found 'x'"},
      {"$NOD\n1\n1 0 0 nan\n$ENDNOD\n",
       "bad.msh:3: expected coordinate z (a finite number), found 'nan'"},
      {"$NOD\n-3\n",
       "bad.msh:2: expected node count (an integer in [0, 1099511627776]), "
       "found '-3'"},
      {"$NOD\n2\n1 0 0 0\n1 1 1 1\n$ENDNOD\n", "bad.msh:4: node 1 is defined twice"},
      {"$NOD\n1\n1 0 0 0\n$ENDNOD\n$ELM\n1\n1 4 0 0 4 1 1 1 7\n$ENDELM\n",
       "bad.msh:7: tetrahedron names node 7, which is not defined"},
      {"$NOD\n1\n1 0 0 0\n$ENDNOD\n$ELM\n1\n1 4 0 0 3 1 1 1\n$ENDELM\n",
       "bad.msh:7: expected 3 tags and 4 node ids for a tetrahedron, found 6 numbers"},
      {"$NOD\n1\n1 0 0 0\n$ENDNOD\n$ELM\n1\n1 5 0 0 8 1 1 1 1 1 1 1 1\n$ENDELM\n",
       "bad.msh:7: element type 5 is not supported: kerf reads linear tetrahedra (type 4); "
       "surface and line elements are skipped"},
      {"$NOD\n1\n1 0 0 0\n$ENDNOD\n",
       "bad.msh:5: expected both $NOD and $ELM sections, "
       "found end of file"},
      {"$MeshFormat\n2.2 1 8\n$EndMeshFormat\n",
       "bad.msh:2: binary MSH is not supported: save the mesh as ASCII"},
      {"$MeshFormat\n3.0 0 8\n$EndMeshFormat\n",
       "bad.msh:2: expected MSH version 2.x, 4.0 or 4.1, found '3.0'"},
      {"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Comments\nno end\n",
       "bad.msh:6: expected '$EndComments', found end of file"},
      {"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$Elements\n",
       "bad.msh:7: expected '$EndNodes', found '$Elements'"},
  };
  for (const BadCase& c : cases) {
    const absl::StatusOr<TetMeshData> data = ParseGmshMsh(c.text, "bad.msh");
    EXPECT_EQ(data.status().code(), absl::StatusCode::kInvalidArgument) << c.text;
    EXPECT_EQ(kerf::testing::StatusMessage(data), c.message) << c.text;
  }
}

TEST(ParseGmshMsh, SharedLiverMeshesLoadAndAreValid) {
  struct Expected {
    const char* name;
    std::size_t vertices, tets;
  };
  for (const Expected& e : {Expected{"liver.msh", 181, 596}, Expected{"liver2.msh", 507, 1493}}) {
    const std::string path = kerf::testing::SharedMeshPath(e.name);
    if (path.empty()) GTEST_SKIP() << "shared/meshes is not beside the repo";
    absl::StatusOr<TetMesh> mesh = ReadMeshFile(path);
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    EXPECT_EQ(mesh->vertex_count(), e.vertices);
    EXPECT_EQ(mesh->tet_count(), e.tets);
    EXPECT_TRUE(ValidateMesh(*mesh).ok()) << ValidateMesh(*mesh);
  }
}

}  // namespace
}  // namespace kerf::mesh
