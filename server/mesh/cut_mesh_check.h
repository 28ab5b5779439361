// Checks a mesh being cut after every change at the cost of the change, finding what the
// whole-mesh checks would: the tets and vertices that changed are valid (mesh_validation.h), the
// tets standing in each original tet that changed keep its rest volume, and the original faces
// of those tets are tiled once and alike from both sides (face_tiling.h). Changes are read from
// the mesh's change log since the last check.
#pragma once

#include <functional>
#include <map>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "absl/status/status.h"
#include "mesh/face_tiling.h"
#include "mesh/mesh_change_log.h"
#include "mesh/tet_mesh.h"

namespace kerf::mesh {

class CutMeshCheck {
 public:
  // `cut` is `uncut` now and changes only by cutting (see CheckOriginalFacesTiled for
  // `source_of` and `same_as`); both must outlive the check. O(tets).
  CutMeshCheck(const TetMesh& uncut, const TetMesh* cut, std::function<TetId(TetId)> source_of,
               std::function<VertexId(VertexId)> same_as);

  // Checks what changed since the last call (or construction). OK, or FAILED_PRECONDITION
  // naming the first defect found. O(tets and vertices changed, and the pieces of their tets).
  absl::Status Check();

 private:
  // Adds the live tet `t` (now a piece of its source) to the bookkeeping.
  void Track(TetId t, absl::flat_hash_set<std::uint32_t>* dirty);
  void Untrack(TetId t, absl::flat_hash_set<std::uint32_t>* dirty);
  // The rest volume and the faces' tiling of the original tet `source`.
  // (`tiles` caches each source's, in a map whose entries stay put.)
  absl::Status CheckSource(TetId source, std::map<std::uint32_t, FaceTiles>* tiles);
  const FaceTiles& TilesOf(TetId source, std::map<std::uint32_t, FaceTiles>* tiles);

  const TetMesh& uncut_;
  const TetMesh* cut_;
  std::function<TetId(TetId)> source_of_;
  std::function<VertexId(VertexId)> same_as_;
  ChangeMark mark_;
  // The original tet across each face of each original tet (tet id, its face), if any.
  absl::flat_hash_map<std::uint64_t, std::pair<TetId, int>> across_;
  absl::flat_hash_map<std::uint32_t, TetId> source_;               // live tet -> its source
  absl::flat_hash_map<std::uint32_t, std::vector<TetId>> pieces_;  // source -> its live tets
};

}  // namespace kerf::mesh
