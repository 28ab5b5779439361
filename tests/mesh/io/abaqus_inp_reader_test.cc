#include "mesh/io/abaqus_inp_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mesh/io/abaqus_inp_blocks.h"
#include "support/status_message.h"

namespace kerf::mesh {
namespace {

using ::testing::ElementsAre;

constexpr char kDeck[] = R"(** a CalculiX deck
*HEADING
two tets
*NODE, NSET=NALL
1, 0.0, 0.0, 0.0
2, 1.0, 0.0, 0.0
3, 0.0, 1.0, 0.0
4, 0.0, 0.0, 1.0
10, 1.0, 1.0, 1.0
*Element, type=c3d4, ELSET=EALL
1, 1, 2, 3, 4
2, 2, 3, 4, 10
*NSET, NSET=FIX
1, 2, 3
*MATERIAL, NAME=TISSUE
*ELASTIC
5000., 0.45
)";

TEST(ParseAbaqusInpMesh, ReadsNodesAndC3D4AndPassesOverTheRest) {
  absl::StatusOr<TetMeshData> data = ParseAbaqusInpMesh(kDeck, "d.inp");
  ASSERT_TRUE(data.ok()) << data.status();
  EXPECT_THAT(data->point_ids, ElementsAre(1, 2, 3, 4, 10));
  ASSERT_EQ(data->tets.size(), 2u);
  EXPECT_THAT(data->tets[1], ElementsAre(1, 2, 3, 4));
}

TEST(ParseInpKeywordBlocks, KeywordsAndParametersAreCaseInsensitive) {
  auto blocks = internal::ParseInpKeywordBlocks(kDeck, "d.inp");
  ASSERT_TRUE(blocks.ok());
  ASSERT_EQ(blocks->size(), 6u);
  EXPECT_EQ((*blocks)[2].keyword, "ELEMENT");
  EXPECT_EQ((*blocks)[2].Parameter("type"), "c3d4");
  EXPECT_EQ((*blocks)[3].Parameter("NSET"), "FIX");
  EXPECT_THAT((*blocks)[3].lines[0].fields, ElementsAre("1", "2", "3"));
}

TEST(ParseAbaqusInpMesh, Errors) {
  const std::pair<std::string, std::string> cases[] = {
      {"1, 0, 0, 0\n", "e.inp:1: expected a *KEYWORD line before data"},
      {"*NODE\n1, 0, 0\n",
       "e.inp:2: expected a *NODE line 'id, x, y, z' with an integer id "
       "and finite coordinates"},
      {"*NODE\n1, 0, 0, 0\n1, 1, 1, 1\n", "e.inp:3: node 1 is defined twice"},
      {"*NODE\n1, 0, 0, 0\n*ELEMENT, TYPE=C3D10\n",
       "e.inp:3: element type 'C3D10' is not "
       "supported: kerf reads linear tetrahedra "
       "(TYPE=C3D4)"},
      {"*NODE\n1, 0, 0, 0\n*ELEMENT, TYPE=C3D4\n1, 1, 1, 1, 2\n",
       "e.inp:4: tetrahedron names node 2, which is not defined"},
      {"*NODE\n1, 0, 0, 0\n", "e.inp:3: expected *NODE and *ELEMENT, TYPE=C3D4 blocks"},
  };
  for (const auto& [text, message] : cases) {
    EXPECT_EQ(kerf::testing::StatusMessage(ParseAbaqusInpMesh(text, "e.inp")), message) << text;
  }
}

}  // namespace
}  // namespace kerf::mesh
