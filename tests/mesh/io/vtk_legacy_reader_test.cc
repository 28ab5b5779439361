#include "mesh/io/vtk_legacy_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/status_message.h"

namespace kerf::mesh {
namespace {

using ::testing::ElementsAre;

constexpr char kClassic[] = R"(# vtk DataFile Version 3.0
two tets and a triangle
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 5 double
0 0 0  1 0 0  0 1 0
0 0 1  1 1 1
CELLS 3 14
4 0 1 2 3
4 1 2 3 4
3 0 1 2
CELL_TYPES 3
10
10
5
POINT_DATA 5
SCALARS t float
)";

constexpr char kOffsets[] = R"(# vtk DataFile Version 5.1
two tets
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 5 float
0 0 0 1 0 0 0 1 0 0 0 1 1 1 1
METADATA
INFORMATION 0

CELLS 3 8
OFFSETS vtktypeint64
0 4 8
CONNECTIVITY vtktypeint64
0 1 2 3 1 2 3 4
CELL_TYPES 2
10 10
)";

void ExpectTheTwoVtkTets(const absl::StatusOr<TetMeshData>& data) {
  ASSERT_TRUE(data.ok()) << data.status();
  ASSERT_EQ(data->points.size(), 5u);
  EXPECT_EQ(data->points[3], Eigen::Vector3d(0, 0, 1));
  ASSERT_EQ(data->tets.size(), 2u);
  EXPECT_THAT(data->tets[1], ElementsAre(1, 2, 3, 4));
}

TEST(ParseVtkLegacy, ClassicCells) { ExpectTheTwoVtkTets(ParseVtkLegacy(kClassic, "a.vtk")); }
TEST(ParseVtkLegacy, Version51OffsetCells) {
  ExpectTheTwoVtkTets(ParseVtkLegacy(kOffsets, "b.vtk"));
}

TEST(ParseVtkLegacy, Errors) {
  const std::string head = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n";
  const std::pair<std::string, std::string> cases[] = {
      {"hello", "bad.vtk:1: expected '# vtk DataFile Version' on the first line, found 'hello'"},
      {"# vtk DataFile Version 3.0\nt\nBINARY\n",
       "bad.vtk:3: binary VTK legacy files are not supported: use ASCII"},
      {"# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\n",
       "bad.vtk:4: expected 'UNSTRUCTURED_GRID', found 'POLYDATA'"},
      {head + "POINTS 1 float\n0 0\n",
       "bad.vtk:7: expected coordinate z (a finite number), "
       "found end of file"},
      {head + "POINTS 1 float\n0 0 0\nCELLS 1 5\n4 0 0 0 3\nCELL_TYPES 1\n10\n",
       "bad.vtk:7: cell 0 names point 3 of 1"},
      {head + "POINTS 1 float\n0 0 0\nCELLS 1 9\n8 0 0 0 0 0 0 0 0\nCELL_TYPES 1\n12\n",
       "bad.vtk:7: cell 0 has type 12, which is not supported: kerf reads tetrahedra (type 10)"},
      {head + "POINTS 1 float\n0 0 0\nCELLS 1 6\n4 0 0 0 0\nCELL_TYPES 1\n10\n",
       "bad.vtk:8: CELLS declares size 6 but its cells hold 5 numbers"},
      {head + "FIELD x 0\n",
       "bad.vtk:5: expected 'POINTS', 'CELLS' or 'CELL_TYPES', found 'FIELD'"},
  };
  for (const auto& [text, message] : cases) {
    const absl::StatusOr<TetMeshData> data = ParseVtkLegacy(text, "bad.vtk");
    EXPECT_EQ(kerf::testing::StatusMessage(data), message) << text;
  }
}

}  // namespace
}  // namespace kerf::mesh
