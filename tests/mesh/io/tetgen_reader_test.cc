#include "mesh/io/tetgen_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/status_message.h"

namespace kerf::mesh {
namespace {

using ::testing::ElementsAre;

constexpr char kNodes[] = R"(# five points, one attribute, markers
5 3 1 1
0  0 0 0  7.5  1
1  1 0 0  7.5  1
2  0 1 0  7.5  0
3  0 0 1  7.5  1
4  1 1 1  7.5  1
)";

constexpr char kTets[] = R"(2 4 0
0  0 1 2 3
1  1 2 3 4   # second
)";

TEST(ParseTetGen, ZeroBasedWithAttributesAndComments) {
  absl::StatusOr<TetMeshData> data = ParseTetGen(kNodes, "m.node", kTets, "m.ele");
  ASSERT_TRUE(data.ok()) << data.status();
  EXPECT_THAT(data->point_ids, ElementsAre(0, 1, 2, 3, 4));
  ASSERT_EQ(data->tets.size(), 2u);
  EXPECT_THAT(data->tets[1], ElementsAre(1, 2, 3, 4));
}

TEST(ParseTetGen, Errors) {
  EXPECT_EQ(kerf::testing::StatusMessage(ParseTetGen("1 2 0 0\n", "m.node", "", "m.ele")),
            "m.node:1: expected dimension (an integer in [3, 3]), found '2'");
  EXPECT_EQ(kerf::testing::StatusMessage(ParseTetGen(kNodes, "m.node", "1 10 0\n", "m.ele")),
            "m.ele:1: 10-node tetrahedra are not supported: kerf reads linear (4-node) "
            "tetrahedra");
  EXPECT_EQ(
      kerf::testing::StatusMessage(ParseTetGen(kNodes, "m.node", "1 4 0\n0 0 1 2 5\n", "m.ele")),
      "m.ele:2: tetrahedron names node 5, which is not defined");
  EXPECT_EQ(
      kerf::testing::StatusMessage(ParseTetGen(kNodes, "m.node", "1 4 0\n0 0 1 2\n", "m.ele")),
      "m.ele:3: expected corner point id (an integer), found end of file");
  EXPECT_EQ(kerf::testing::StatusMessage(
                ParseTetGen("1 3 0 0\n0 0 0 0\n1 1 1 1\n", "m.node", "", "m.ele")),
            "m.node:3: expected end of file after 1 points, found '1'");
}

}  // namespace
}  // namespace kerf::mesh
