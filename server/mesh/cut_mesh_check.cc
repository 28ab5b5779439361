#include "mesh/cut_mesh_check.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "mesh/mesh_validation.h"

namespace kerf::mesh {
namespace {

std::uint64_t FaceOf(TetId t, int k) { return (std::uint64_t{Index(t)} << 2) | k; }

}  // namespace

CutMeshCheck::CutMeshCheck(const TetMesh& uncut, const TetMesh* cut,
                           std::function<TetId(TetId)> source_of,
                           std::function<VertexId(VertexId)> same_as)
    : uncut_(uncut),
      cut_(cut),
      source_of_(std::move(source_of)),
      same_as_(std::move(same_as)),
      mark_(cut->change_log().Mark()) {
  absl::flat_hash_map<std::array<std::uint32_t, 3>, std::pair<TetId, int>> first_side;
  for (const TetId t : uncut.tets()) {
    const TetVertices& corners = uncut.tet(t);
    for (int k = 0; k < 4; ++k) {
      const auto& f = kTetFaces[k];
      std::array<std::uint32_t, 3> key = {Index(corners[f[0]]), Index(corners[f[1]]),
                                          Index(corners[f[2]])};
      std::sort(key.begin(), key.end());
      const auto [other, fresh] = first_side.try_emplace(key, t, k);
      if (fresh) continue;
      across_[FaceOf(t, k)] = other->second;
      across_[FaceOf(other->second.first, other->second.second)] = {t, k};
    }
  }
  for (const TetId t : cut->tets()) Track(t, nullptr);
}

void CutMeshCheck::Track(TetId t, absl::flat_hash_set<std::uint32_t>* dirty) {
  const TetId source = source_of_(t);
  source_[Index(t)] = source;
  pieces_[Index(source)].push_back(t);
  if (dirty != nullptr) dirty->insert(Index(source));
}

void CutMeshCheck::Untrack(TetId t, absl::flat_hash_set<std::uint32_t>* dirty) {
  const auto it = source_.find(Index(t));
  if (it == source_.end()) return;  // added and removed since the last check
  std::vector<TetId>& pieces = pieces_[Index(it->second)];
  pieces.erase(std::find(pieces.begin(), pieces.end(), t));
  dirty->insert(Index(it->second));
  source_.erase(it);
}

absl::Status CutMeshCheck::Check() {
  const absl::StatusOr<MeshChanges> changes = cut_->change_log().ChangesSince(mark_);
  if (!changes.ok()) return changes.status();
  mark_ = cut_->change_log().Mark();
  absl::flat_hash_set<std::uint32_t> dirty;
  std::vector<TetId> tets = changes->added_tets;
  std::vector<VertexId> vertices = changes->added_vertices;
  for (std::size_t i = 0; i < changes->removed_tets.size(); ++i) {
    const TetVertices& corners = changes->removed_tet_corners[i];
    vertices.insert(vertices.end(), corners.begin(), corners.end());
    Untrack(changes->removed_tets[i], &dirty);
  }
  for (const TetId t : changes->added_tets) Track(t, &dirty);
  for (const VertexId v : changes->moved_vertices) {
    if (!cut_->IsAlive(v)) continue;
    for (const TetId t : cut_->TetsAround(v)) {
      tets.push_back(t);
      dirty.insert(Index(source_.at(Index(t))));
    }
  }
  if (absl::Status s = ValidateMeshAmong(*cut_, tets, vertices); !s.ok()) return s;
  std::vector<std::uint32_t> sources(dirty.begin(), dirty.end());
  std::sort(sources.begin(), sources.end());  // the first defect found whatever the hash order
  std::map<std::uint32_t, FaceTiles> tiles;
  for (const std::uint32_t s : sources) {
    if (absl::Status status = CheckSource(TetId(s), &tiles); !status.ok()) return status;
  }
  return absl::OkStatus();
}

const FaceTiles& CutMeshCheck::TilesOf(TetId source, std::map<std::uint32_t, FaceTiles>* tiles) {
  const auto [it, fresh] = tiles->try_emplace(Index(source));
  if (fresh) it->second = TilesOfSource(uncut_, *cut_, source, pieces_[Index(source)]);
  return it->second;
}

absl::Status CutMeshCheck::CheckSource(TetId source, std::map<std::uint32_t, FaceTiles>* tiles) {
  double volume = 0;
  for (const TetId piece : pieces_[Index(source)]) volume += RestVolume(*cut_, piece);
  const double whole = RestVolume(uncut_, source);
  if (std::abs(volume - whole) > 1e-12 * whole) {
    return absl::FailedPreconditionError(absl::StrCat("the tets cut from tet ", Index(source),
                                                      " have rest volume ", volume, " instead of ",
                                                      whole));
  }
  for (int k = 0; k < 4; ++k) {
    std::optional<OtherSide> other;
    if (const auto it = across_.find(FaceOf(source, k)); it != across_.end()) {
      other = OtherSide{it->second.first, &TilesOf(it->second.first, tiles)[it->second.second]};
    }
    if (absl::Status s =
            CheckFaceTiled(uncut_, *cut_, source, k, TilesOf(source, tiles)[k], other, same_as_);
        !s.ok()) {
      return s;
    }
  }
  return absl::OkStatus();
}

}  // namespace kerf::mesh
