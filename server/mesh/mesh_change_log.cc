#include "mesh/mesh_change_log.h"

#include <algorithm>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "absl/strings/str_cat.h"

namespace kerf::mesh {
namespace {

// Net effect of the events on one id: +1 added, -1 removed, 0 added and removed again.
// Ids are never reused, so an id is added at most once and removed at most once.
template <typename Id>
std::vector<Id> SortedIdsWithNet(const absl::flat_hash_map<std::uint32_t, int>& net, int sign) {
  std::vector<Id> ids;
  for (const auto& [id, value] : net) {
    if (value == sign) ids.push_back(static_cast<Id>(id));
  }
  std::sort(ids.begin(), ids.end());
  return ids;
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
  absl::flat_hash_map<std::uint32_t, int> vertex_net, tet_net;
  absl::flat_hash_set<std::uint32_t> moved;
  for (std::size_t i = since.sequence - first_kept_; i < events_.size(); ++i) {
    const Event& e = events_[i];
    switch (e.kind) {
      case Kind::kAddVertex:
        vertex_net[e.id] += 1;
        break;
      case Kind::kRemoveVertex:
        vertex_net[e.id] -= 1;
        break;
      case Kind::kAddTet:
        tet_net[e.id] += 1;
        break;
      case Kind::kRemoveTet:
        tet_net[e.id] -= 1;
        break;
      case Kind::kMoveVertex:
        moved.insert(e.id);
        break;
    }
  }
  MeshChanges changes;
  changes.added_vertices = SortedIdsWithNet<VertexId>(vertex_net, +1);
  changes.removed_vertices = SortedIdsWithNet<VertexId>(vertex_net, -1);
  changes.added_tets = SortedIdsWithNet<TetId>(tet_net, +1);
  changes.removed_tets = SortedIdsWithNet<TetId>(tet_net, -1);
  for (const std::uint32_t id : moved) {
    // One added or removed in the interval is listed as such.
    if (!vertex_net.contains(id)) changes.moved_vertices.push_back(static_cast<VertexId>(id));
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
