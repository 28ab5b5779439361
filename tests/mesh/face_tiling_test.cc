#include "mesh/face_tiling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/match.h"
#include "mesh/box_lattice.h"
#include "support/status_message.h"

namespace kerf::mesh {
namespace {

using kerf::testing::StatusMessage;

// Replaces tet t by the three tets of a fan from a new point in the middle of its face k
// (corner k stays the apex of each), recording where they came from.
void FanFace(TetMesh* m, TetId t, int k, absl::flat_hash_map<TetId, TetId>* source) {
  const TetVertices v = m->tet(t);
  const auto& f = kTetFaces[k];
  const VertexId middle = m->AddVertex(
      (m->rest_position(v[f[0]]) + m->rest_position(v[f[1]]) + m->rest_position(v[f[2]])) / 3);
  ASSERT_TRUE(m->RemoveTet(t).ok());
  for (int n = 0; n < 3; ++n) {
    // Same orientation as (corner k, f[n], f[n+1], middle) inherits from the original tet.
    const absl::StatusOr<TetId> added = m->AddTet({v[f[n]], v[f[(n + 1) % 3]], middle, v[k]});
    ASSERT_TRUE(added.ok());
    (*source)[*added] = source->contains(t) ? source->at(t) : t;
  }
}

// A face of the uncut mesh shared by two tets, as (tet, local face) on each side; the lattice's
// first tet has one.
struct SharedFace {
  TetId a, b;
  int face_of_a, face_of_b;
};

std::optional<SharedFace> FindSharedFace(const TetMesh& m, bool interior) {
  for (const TetId t : m.tets()) {
    const TetVertices& v = m.tet(t);
    for (int k = 0; k < 4; ++k) {
      const auto& f = kTetFaces[k];
      const TetMesh::TetList around = m.TetsAroundFace(v[f[0]], v[f[1]], v[f[2]]);
      if (interior != (around.size() == 2)) continue;
      if (!interior) return SharedFace{t, t, k, k};
      const TetId other = around[0] == t ? around[1] : around[0];
      for (int j = 0; j < 4; ++j) {
        const auto& g = kTetFaces[j];
        const TetVertices& w = m.tet(other);
        if (m.TetsAroundFace(w[g[0]], w[g[1]], w[g[2]]).size() == 2 &&
            std::is_permutation(f.begin(), f.end(), g.begin(),
                                [&](int x, int y) { return v[x] == w[y]; })) {
          return SharedFace{t, other, k, j};
        }
      }
    }
  }
  return std::nullopt;
}

class FaceTiling : public ::testing::Test {
 protected:
  FaceTiling() : uncut_(*MakeBoxLattice({.cells_x = 2, .size = {2, 1, 1}})), cut_(uncut_) {}
  absl::Status Check() const {
    return CheckOriginalFacesTiled(uncut_, cut_, [&](TetId t) {
      const auto it = source_.find(t);
      return it == source_.end() ? t : it->second;
    });
  }
  TetMesh uncut_;
  TetMesh cut_;
  absl::flat_hash_map<TetId, TetId> source_;
};

TEST_F(FaceTiling, AnUncutMeshIsTiled) { EXPECT_TRUE(Check().ok()) << Check(); }

TEST_F(FaceTiling, AnInteriorFaceSplitOnOneSideOnlyIsFound) {
  const std::optional<SharedFace> shared = FindSharedFace(uncut_, true);
  ASSERT_TRUE(shared.has_value());
  FanFace(&cut_, shared->a, shared->face_of_a, &source_);
  EXPECT_TRUE(absl::StrContains(StatusMessage(Check()), "is split differently in the pieces"))
      << Check();
}

TEST_F(FaceTiling, ABoundaryFaceMaySplitAlone) {
  const std::optional<SharedFace> boundary = FindSharedFace(uncut_, false);
  ASSERT_TRUE(boundary.has_value());
  FanFace(&cut_, boundary->a, boundary->face_of_a, &source_);
  EXPECT_TRUE(Check().ok()) << Check();
}

// A crack along an interior face: one side's tet takes copies of the face's three vertices.
// Only taken as the copies' originals does the face read alike from both sides.
TEST_F(FaceTiling, AFaceOnACrackIsAlikeTakingCopiesAsTheirOriginals) {
  const std::optional<SharedFace> shared = FindSharedFace(uncut_, true);
  ASSERT_TRUE(shared.has_value());
  TetVertices moved = cut_.tet(shared->b);
  absl::flat_hash_map<VertexId, VertexId> original_of;
  for (const int corner : kTetFaces[shared->face_of_b]) {
    const VertexId copy = cut_.AddVertex(cut_.rest_position(moved[corner]));
    original_of[copy] = moved[corner];
    moved[corner] = copy;
  }
  ASSERT_TRUE(cut_.RemoveTet(shared->b).ok());
  const absl::StatusOr<TetId> added = cut_.AddTet(moved);
  ASSERT_TRUE(added.ok());
  source_[*added] = shared->b;
  EXPECT_TRUE(absl::StrContains(StatusMessage(Check()), "is split differently in the pieces"));
  const absl::Status as_originals = CheckOriginalFacesTiled(
      uncut_, cut_, [&](TetId t) { return source_.contains(t) ? source_.at(t) : t; },
      [&](VertexId v) { return original_of.contains(v) ? original_of.at(v) : v; });
  EXPECT_TRUE(as_originals.ok()) << as_originals;
}

TEST_F(FaceTiling, AFaceCoveredTwiceIsFound) {
  // A tet of the cut mesh added over one already there: its faces are tiled twice.
  const TetId first = *uncut_.tets().begin();
  const TetVertices corners = cut_.tet(first);
  const absl::StatusOr<TetId> again = cut_.AddTet(corners);
  ASSERT_TRUE(again.ok());
  source_[*again] = first;
  EXPECT_TRUE(absl::StrContains(StatusMessage(Check()), "is tiled 2 times")) << Check();
}

}  // namespace
}  // namespace kerf::mesh
