#include "sim/abaqus_deck.h"

#include <gtest/gtest.h>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "support/status_message.h"

namespace kerf::sim {
namespace {

using kerf::testing::StatusMessage;

constexpr char kDeck[] = R"(*HEADING
one tet
*NODE, NSET=NALL
1, 0.0, 0.0, 0.0
2, 1.0, 0.0, 0.0
3, 0.0, 1.0, 0.0
4, 0.0, 0.0, 1.0
*ELEMENT, TYPE=C3D4, ELSET=EALL
1, 1, 2, 3, 4
*NSET, NSET=FIX
1, 2
*NSET, NSET=TOP, GENERATE
3, 4, 1
*MATERIAL, NAME=TISSUE
*ELASTIC
5000., 0.45
*DENSITY
2.
*SOLID SECTION, ELSET=EALL, MATERIAL=TISSUE
*BOUNDARY
FIX, 1, 3, 0.
3, 2, , 0.25
*STEP
*STATIC
*CLOAD
TOP, 3, -0.5
*DLOAD
EALL, GRAV, 9.81, 0., 0., -1.
*NODE PRINT, NSET=NALL
U
*END STEP
)";

TEST(ParseStaticDeck, ReadsMaterialSetsConditionsAndLoads) {
  absl::StatusOr<StaticDeck> deck = ParseStaticDeck(kDeck, "d.inp");
  ASSERT_TRUE(deck.ok()) << deck.status();
  EXPECT_EQ(deck->mesh.tet_count(), 1u);
  EXPECT_EQ(deck->material.youngs_modulus, 5000);
  EXPECT_EQ(deck->material.poisson_ratio, 0.45);
  EXPECT_EQ(deck->material.density, 2);
  ASSERT_EQ(deck->conditions.prescribed.size(), 7u);  // 2 nodes x 3 dofs, then node 3 dof 2
  EXPECT_EQ(deck->conditions.prescribed[6].vertex, mesh::VertexId{2});
  EXPECT_EQ(deck->conditions.prescribed[6].component, 1);
  EXPECT_EQ(deck->conditions.prescribed[6].value, 0.25);
  ASSERT_EQ(deck->conditions.loads.size(), 2u);  // each node of TOP gets the full value
  EXPECT_EQ(deck->conditions.loads[1].force, Eigen::Vector3d(0, 0, -0.5));
  EXPECT_EQ(deck->conditions.gravity, Eigen::Vector3d(0, 0, -9.81));
}

TEST(ParseStaticDeck, RefusesWhatIsOutsideTheSubsetByName) {
  const std::pair<std::string, std::string> cases[] = {
      {absl::StrReplaceAll(kDeck, {{"*STATIC", "*DYNAMIC"}}),
       "d.inp:24: *DYNAMIC is not supported by kerf static; the subset is in "
       "../shared/design/accuracy.md"},
      {absl::StrReplaceAll(kDeck, {{"EALL, GRAV", "EALL, P1"}}),
       "d.inp:28: expected 'elset, GRAV, magnitude, dx, dy, dz': kerf supports only gravity "
       "loads"},
      {absl::StrReplaceAll(kDeck, {{"TOP, 3, -0.5", "TOP, 5, -0.5"}}),
       "d.inp:26: expected 'node or set, dof (1-3), value'"},
      {absl::StrReplaceAll(kDeck, {{"FIX, 1, 3, 0.", "FIX, 4, 6, 0."}}),
       "d.inp:21: dofs 4 to 6 are not translations: kerf supports dofs 1-3"},
      {absl::StrReplaceAll(kDeck, {{"TOP, 3, -0.5", "BOTTOM, 3, -0.5"}}),
       "d.inp:26: 'BOTTOM' is neither a node id nor a node set"},
      {absl::StrReplaceAll(kDeck, {{"3, 2, , 0.25", "9, 2, , 0.25"}}),
       "d.inp:22: node 9 is not defined"},
      {absl::StrReplaceAll(kDeck, {{"*ELASTIC", "*ELASTIC, TYPE=ORTHO"}}),
       "d.inp:15: expected *ELASTIC (isotropic) with one line 'E, nu'"},
      {absl::StrReplaceAll(kDeck, {{"5000., 0.45", "5000., 0.5"}}),
       "poisson_ratio must be strictly between -1 and 0.5, got 0.5"},
      {absl::StrReplaceAll(kDeck, {{"ELSET=EALL, MATERIAL", "ELSET=SOME, MATERIAL"}}),
       "d.inp:19: *SOLID SECTION must assign material TISSUE to element set EALL, every "
       "element"},
      {absl::StrReplaceAll(kDeck, {{"TYPE=C3D4", "TYPE=C3D10"}}),
       "d.inp:8: element type 'C3D10' is not supported: kerf reads linear tetrahedra "
       "(TYPE=C3D4)"},
  };
  for (const auto& [text, message] : cases) {
    EXPECT_EQ(StatusMessage(ParseStaticDeck(text, "d.inp")), message);
  }
}

}  // namespace
}  // namespace kerf::sim
