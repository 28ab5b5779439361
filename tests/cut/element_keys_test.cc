#include "cut/element_keys.h"

#include <gtest/gtest.h>

namespace kerf::cut {
namespace {

using mesh::VertexId;

TEST(ElementKeys, AnEdgeIsNamedAlikeFromEitherEndAndGivesItsEndsBack) {
  const EdgeKey key = MakeEdgeKey(VertexId(7), VertexId(3));
  EXPECT_EQ(key, MakeEdgeKey(VertexId(3), VertexId(7)));
  EXPECT_EQ(EdgeEnds(key), (std::array<VertexId, 2>{VertexId(3), VertexId(7)}));
  EXPECT_EQ(EdgeEnds(MakeEdgeKey(VertexId(0xfffffffeu), VertexId(0))),
            (std::array<VertexId, 2>{VertexId(0), VertexId(0xfffffffeu)}));
}

TEST(ElementKeys, AFaceIsNamedAlikeInAnyOrder) {
  const FaceKey key = MakeFaceKey(VertexId(5), VertexId(1), VertexId(9));
  EXPECT_EQ(key, (FaceKey{VertexId(1), VertexId(5), VertexId(9)}));
  EXPECT_EQ(key, MakeFaceKey(VertexId(9), VertexId(5), VertexId(1)));
  EXPECT_EQ(FaceKeyHash()(key), FaceKeyHash()(MakeFaceKey(VertexId(1), VertexId(9), VertexId(5))));
}

}  // namespace
}  // namespace kerf::cut
