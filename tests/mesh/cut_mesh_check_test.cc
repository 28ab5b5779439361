#include "mesh/cut_mesh_check.h"

#include <gtest/gtest.h>

#include <iterator>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/match.h"
#include "geometry/tet_measures.h"
#include "mesh/box_lattice.h"
#include "mesh/face_tiling.h"
#include "mesh/mesh_validation.h"
#include "support/status_message.h"

namespace kerf::mesh {
namespace {

using kerf::testing::StatusMessage;

// A lattice being cut by hand: edits recorded with where each new tet came from.
class HandCut {
 public:
  HandCut() : uncut_(*MakeBoxLattice({.cells_x = 2, .cells_y = 2, .cells_z = 2})), cut_(uncut_) {}

  TetId SourceOf(TetId t) const {
    const auto it = source_.find(t);
    return it == source_.end() ? t : it->second;
  }
  // Replaces tet t by four tets from a new point at its middle.
  void Star(TetId t) {
    const TetVertices v = cut_.tet(t);
    const VertexId middle = cut_.AddVertex((cut_.rest_position(v[0]) + cut_.rest_position(v[1]) +
                                            cut_.rest_position(v[2]) + cut_.rest_position(v[3])) /
                                           4);
    const TetId source = SourceOf(t);
    ASSERT_TRUE(cut_.RemoveTet(t).ok());
    for (int k = 0; k < 4; ++k) {
      TetVertices piece = v;
      piece[k] = middle;
      const absl::StatusOr<TetId> added = cut_.AddTet(piece);
      ASSERT_TRUE(added.ok());
      source_[*added] = source;
    }
  }
  // Replaces tet t by the three tets of a fan from a new point in the middle of its face k: the
  // tet across that face is not split alike.
  void FanFace(TetId t, int k) {
    const TetVertices v = cut_.tet(t);
    const auto& f = kTetFaces[k];
    const VertexId middle = cut_.AddVertex(
        (cut_.rest_position(v[f[0]]) + cut_.rest_position(v[f[1]]) + cut_.rest_position(v[f[2]])) /
        3);
    const TetId source = SourceOf(t);
    ASSERT_TRUE(cut_.RemoveTet(t).ok());
    for (int n = 0; n < 3; ++n) {
      TetVertices piece = {v[f[n]], v[f[(n + 1) % 3]], middle, v[k]};
      const auto x = [&](int i) { return cut_.rest_position(piece[i]); };
      if (geometry::SignedVolume(x(0), x(1), x(2), x(3)) < 0) std::swap(piece[0], piece[1]);
      const absl::StatusOr<TetId> added = cut_.AddTet(piece);
      ASSERT_TRUE(added.ok());
      source_[*added] = source;
    }
  }
  absl::Status Full() const {
    if (absl::Status s = ValidateMesh(cut_); !s.ok()) return s;
    return CheckOriginalFacesTiled(uncut_, cut_, [&](TetId t) { return SourceOf(t); });
  }

  TetMesh uncut_;
  TetMesh cut_;
  absl::flat_hash_map<TetId, TetId> source_;
};

TEST(CutMeshCheck, FindsWhatTheWholeMeshChecksFindAfterEachChange) {
  HandCut hand;
  CutMeshCheck check(hand.uncut_, &hand.cut_, [&](TetId t) { return hand.SourceOf(t); }, {});
  EXPECT_TRUE(check.Check().ok());
  // Stars keep every property; each checked as it is made, and again once more made.
  for (const TetId t : {TetId(0), TetId(5), TetId(17)}) {
    hand.Star(t);
    EXPECT_TRUE(hand.Full().ok());
    const absl::Status status = check.Check();
    EXPECT_TRUE(status.ok()) << status;
  }
  hand.Star(*std::next(hand.cut_.tets().begin(), 3));
  EXPECT_TRUE(check.Check().ok());
  // A face fanned on one side only: the pieces across it tile it differently.
  const TetId fanned = *hand.cut_.tets().begin();
  hand.FanFace(fanned, 0);
  const absl::Status full = hand.Full();
  const absl::Status incremental = check.Check();
  EXPECT_FALSE(full.ok());
  EXPECT_FALSE(incremental.ok());
  EXPECT_TRUE(absl::StrContains(StatusMessage(incremental), "tiled") ||
              absl::StrContains(StatusMessage(incremental), "split differently"))
      << incremental;
}

TEST(CutMeshCheck, FindsALostTetAndAnUnusedVertex) {
  HandCut hand;
  CutMeshCheck check(hand.uncut_, &hand.cut_, [&](TetId t) { return hand.SourceOf(t); }, {});
  ASSERT_TRUE(hand.cut_.RemoveTet(TetId(7)).ok());
  const absl::Status lost = check.Check();
  EXPECT_FALSE(lost.ok());
  EXPECT_TRUE(absl::StrContains(StatusMessage(lost), "used by no tet") ||
              absl::StrContains(StatusMessage(lost), "rest volume"))
      << lost;
}

}  // namespace
}  // namespace kerf::mesh
