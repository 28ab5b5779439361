#include "mesh/mesh_change_log.h"

#include <algorithm>
#include <utility>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "absl/strings/str_cat.h"

namespace kerf::mesh {
namespace {

// One id's life over an interval: whether it was alive at the start (its first event is a
// removal) and is alive at the end (its last event is an addition), and the corners of its first
// removal (tets only).
struct Life {
  bool alive_before = false;
  bool alive_after = false;
  TetVertices corners_before{};
};

void Record(absl::flat_hash_map<std::uint32_t, Life>& lives, std::uint32_t id, bool added,
            const TetVertices& corners) {
  const auto [it, first] = lives.try_emplace(id);
  if (first) {
    it->second.alive_before = !added;
    it->second.corners_before = corners;
  }
  it->second.alive_after = added;
}

// The ids alive at the end and not at the start, or alive at the start and not at the end; an id
// alive at both ends with events between was removed and its id taken by a new element: both.
template <typename Id>
void Net(const absl::flat_hash_map<std::uint32_t, Life>& lives, std::vector<Id>* added,
         std::vector<std::pair<Id, TetVertices>>* removed) {
  for (const auto& [id, life] : lives) {
    if (life.alive_after) added->push_back(static_cast<Id>(id));
    if (life.alive_before) removed->push_back({static_cast<Id>(id), life.corners_before});
  }
  std::sort(added->begin(), added->end());
  std::sort(removed->begin(), removed->end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
}

}  // namespace

absl::StatusOr<MeshChanges> MeshChangeLog::ChangesSince(ChangeMark since) const {
  if (since.sequence < first_kept_) {
    return absl::OutOfRangeError(absl::StrCat("changes since sequence ", since.sequence,
                                              " were discarded (history starts at ", first_kept_,
                                              "); take a full snapshot"));
  }
  if (since.sequence > Mark().sequence) {
    return absl::OutOfRangeError(absl::StrCat(
        "sequence ", since.sequence, " is past the end of the log (", Mark().sequence, ")"));
  }
  absl::flat_hash_map<std::uint32_t, Life> vertex_lives, tet_lives;
  absl::flat_hash_set<std::uint32_t> moved;
  for (std::size_t i = since.sequence - first_kept_; i < events_.size(); ++i) {
    const Event& e = events_[i];
    switch (e.kind) {
      case Kind::kAddVertex:
      case Kind::kRemoveVertex:
        Record(vertex_lives, e.id, e.kind == Kind::kAddVertex, {});
        break;
      case Kind::kAddTet:
      case Kind::kRemoveTet:
        Record(tet_lives, e.id, e.kind == Kind::kAddTet, e.corners);
        break;
      case Kind::kMoveVertex:
        moved.insert(e.id);
        break;
    }
  }
  MeshChanges changes;
  std::vector<std::pair<VertexId, TetVertices>> removed_vertices;
  Net(vertex_lives, &changes.added_vertices, &removed_vertices);
  for (const auto& [v, unused] : removed_vertices) changes.removed_vertices.push_back(v);
  std::vector<std::pair<TetId, TetVertices>> removed_tets;
  Net(tet_lives, &changes.added_tets, &removed_tets);
  for (const auto& [t, corners] : removed_tets) {
    changes.removed_tets.push_back(t);
    changes.removed_tet_corners.push_back(corners);
  }
  for (const std::uint32_t id : moved) {
    // One added or removed in the interval is listed as such.
    if (!vertex_lives.contains(id)) changes.moved_vertices.push_back(static_cast<VertexId>(id));
  }
  std::sort(changes.moved_vertices.begin(), changes.moved_vertices.end());
  return changes;
}

void MeshChangeLog::DiscardBefore(ChangeMark mark) {
  if (mark.sequence <= first_kept_) return;
  const std::uint64_t drop = std::min<std::uint64_t>(mark.sequence - first_kept_, events_.size());
  events_.erase(events_.begin(), events_.begin() + static_cast<std::ptrdiff_t>(drop));
  first_kept_ += drop;
}

}  // namespace kerf::mesh
