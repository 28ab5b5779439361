// The copies of vertices a crack parts. A vertex the crack runs through has a copy for each
// part of its tets but one: the tets around it (and around its copies), joined through their
// faces at it that are not crack faces, form parts. Faces and crack faces are compared by their
// vertices' origins (a copy's origin is the vertex it was made from), so the parts are a
// function of the crack alone: a crack face added later parts a vertex further; tets that were
// rebuilt (a temporary split following the blade) are joined back to the parts they touch.
//
// Each part keeps the id most of its tets already use (larger parts choose first), so a tet
// changes its vertex only where parts merge: a side of an opened crack never jumps to the other
// side's place. A part left with none takes the origin if no part kept it, else a new copy,
// either starting at the place (and, for the simulation, the state) its tets had the vertex at;
// where every part kept a copy, the largest takes the origin in its copy's place (the origin
// stays in use: it names the vertex).
// A copy no part uses any more is removed. A vertex on the crack's front (the crack ends at it)
// has one part and stays whole.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "cut/element_keys.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {

// Crack faces, by their vertices' origins.
using CrackFaceSet = absl::flat_hash_set<FaceKey, FaceKeyHash>;

struct VertexCopy {
  mesh::VertexId copy;
  mesh::VertexId from;  // the vertex whose place (and state) it starts from
};

struct PartingChanges {
  std::vector<VertexCopy> made;         // new copies, and origins taken up again by another part
  std::vector<mesh::VertexId> removed;  // copies no part uses
  std::vector<std::pair<mesh::TetId, mesh::TetId>> replaced;  // old tet, the tet in its place
};

class VertexParting {
 public:
  // The vertex a copy was made from (v itself for a vertex that is no copy).
  mesh::VertexId Origin(mesh::VertexId v) const {
    const std::uint32_t i = mesh::Index(v);
    return i < origin_.size() && origin_[i] != kNoOrigin ? origin_[i] : v;
  }
  bool HasCopies(mesh::VertexId origin) const {
    const auto it = copies_.find(origin);
    return it != copies_.end() && !it->second.empty();
  }
  // The origin and its live copies.
  std::vector<mesh::VertexId> Ids(mesh::VertexId origin) const;
  // Every origin with copies, and the copies. O(copies).
  void AddNamedVertices(absl::flat_hash_set<mesh::VertexId>* named) const;
  // The live tets using the origin or one of its copies.
  std::vector<mesh::TetId> TetsAround(const mesh::TetMesh& mesh, mesh::VertexId origin) const;
  // The key of a face by its vertices' origins.
  FaceKey OriginKey(mesh::VertexId a, mesh::VertexId b, mesh::VertexId c) const {
    return MakeFaceKey(Origin(a), Origin(b), Origin(c));
  }

  // Parts each of `origins` (or the origins of copies given) by the crack (`on_crack` of a face's
  // origin key), rewriting the tets whose id for it changes. `fresh` (if given) names tets just
  // made from origins: the id they use tells nothing of their side, so a part chooses its id, and
  // the place a new copy starts from, by its other tets where it has any. O(stars).
  PartingChanges Repart(mesh::TetMesh* mesh, const std::vector<mesh::VertexId>& origins,
                        const std::function<bool(const FaceKey&)>& on_crack,
                        const std::function<bool(mesh::TetId)>& fresh = nullptr);
  // Removes the origin and its copies if no tet uses them; false if a tet does.
  bool RemoveIfUnused(mesh::TetMesh* mesh, mesh::VertexId origin);

 private:
  // The id `t` uses for `origin` (it must use one).
  mesh::VertexId IdIn(const mesh::TetMesh& mesh, mesh::TetId t, mesh::VertexId origin) const;
  // The parts of the star of `o` (indices into `star`): tets joined through faces at o that are
  // not on the crack, larger parts first.
  std::vector<std::vector<int>> PartsOfStar(
      const mesh::TetMesh& mesh, mesh::VertexId o, const std::vector<mesh::TetId>& star,
      const std::function<bool(const FaceKey&)>& on_crack) const;
  // The id each part uses for `o` (see the class comment), making the copies that takes.
  std::vector<mesh::VertexId> IdsOfParts(mesh::TetMesh* mesh, mesh::VertexId o,
                                         const std::vector<mesh::TetId>& star,
                                         const std::vector<std::vector<int>>& parts,
                                         const std::function<bool(mesh::TetId)>& is_fresh,
                                         PartingChanges* changes);

  static constexpr mesh::VertexId kNoOrigin{0xffffffffu};
  // By vertex index: a copy's origin, kNoOrigin for a vertex that is no copy (a dense array:
  // Origin is asked for every corner of every tet near the blade at every pose).
  std::vector<mesh::VertexId> origin_;
  absl::flat_hash_map<mesh::VertexId, std::vector<mesh::VertexId>> copies_;  // origin -> copies
};

}  // namespace kerf::cut
