// Properties 2 and 6 of a cut (shared/design/cutting.md), checked on the faces of the mesh
// before the cut: each face of each uncut tet is tiled exactly once by the faces of the tets
// that came from it, and an interior face is tiled by the same triangles from both sides
// (the cut crosses faces, so no part of an interior face lies on it).
//
// Faces inside an uncut tet (between pieces, or on a crack) are not checked here: a crack's two
// sides may be tiled differently once a later cut crosses it, which is no defect.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "absl/status/status.h"
#include "mesh/tet_mesh.h"

namespace kerf::mesh {

// The faces of `pieces` that lie on face k (kTetFaces) of the tet `corners`, each with its
// vertex ids sorted, the list sorted: the faces whose three vertices lie, at rest, within a
// billionth of the tet's height of the face's plane. O(pieces).
std::vector<std::array<VertexId, 3>> TrianglesOnFace(const TetMesh& mesh,
                                                     const TetVertices& corners, int k,
                                                     std::span<const TetVertices> pieces);

// The triangles of `pieces` (live tets of `cut`, its vertices at the rest positions `uncut`'s
// have) on each face of `uncut`'s tet `source`, each face's list sorted. O(pieces).
using FaceTiles = std::array<std::vector<std::array<VertexId, 3>>, 4>;
FaceTiles TilesOfSource(const TetMesh& uncut, const TetMesh& cut, TetId source,
                        std::span<const TetId> pieces);

// Face k of `source` is tiled once by `tiles` (its area, to 1e-9); and where `other` is given
// (the tet across the face, and the triangles on its side), alike from both sides once each
// vertex is taken as `same_as(v)`. OK, or FAILED_PRECONDITION naming the face.
struct OtherSide {
  TetId tet;
  const std::vector<std::array<VertexId, 3>>* tiles;
};
absl::Status CheckFaceTiled(const TetMesh& uncut, const TetMesh& cut, TetId source, int k,
                            const std::vector<std::array<VertexId, 3>>& tiles,
                            const std::optional<OtherSide>& other,
                            const std::function<VertexId(VertexId)>& same_as);

// `cut` is `uncut` after cutting: its vertices keep their ids and rest positions, and
// `source_of(t)` is the tet of `uncut` that live tet t of `cut` came from. An interior face is
// tiled alike from both sides, or lies on the cut: alike once each vertex is taken as
// `same_as(v)` (a vertex copied where a crack runs through it, as its original; unset: every
// vertex as itself). OK, or FAILED_PRECONDITION naming the first face tiled wrongly.
// O(tets of cut + faces of uncut).
absl::Status CheckOriginalFacesTiled(const TetMesh& uncut, const TetMesh& cut,
                                     const std::function<TetId(TetId)>& source_of,
                                     const std::function<VertexId(VertexId)>& same_as = {});

}  // namespace kerf::mesh
