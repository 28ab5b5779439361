// The record of topology changes to a mesh, from which a later layer streams deltas.
//
// Every addition and removal of a vertex or tet, and every move of a vertex's rest position,
// is appended as an event with a sequence number. A consumer takes a Mark, and later asks for the
// net changes since it, judged by each id's life: an id alive at the mark and alive now that was
// removed in between (its id reused by a new element, see TetMesh) is in both lists, removed and
// added; one added and removed again within the interval is in neither. A removed tet's event
// keeps its corners, so a consumer learns what left even after its id was reused. Events older
// than a mark can be discarded to bound memory; asking for changes since a discarded point is an
// error, on which a consumer falls back to a full snapshot.
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "mesh/mesh_ids.h"

namespace kerf::mesh {

// A position in the change log: the number of events recorded before it.
struct ChangeMark {
  std::uint64_t sequence = 0;
  friend bool operator==(ChangeMark, ChangeMark) = default;
};

// Net topology changes over an interval, each list in increasing id order.
struct MeshChanges {
  std::vector<VertexId> added_vertices;
  std::vector<VertexId> removed_vertices;
  std::vector<TetId> added_tets;
  std::vector<TetId> removed_tets;
  // The corners each of removed_tets had at the start of the interval, in the same order.
  std::vector<TetVertices> removed_tet_corners;
  // Vertices neither added nor removed that took a new rest position (TetMesh::MoveVertex).
  std::vector<VertexId> moved_vertices;

  bool empty() const {
    return added_vertices.empty() && removed_vertices.empty() && added_tets.empty() &&
           removed_tets.empty() && moved_vertices.empty();
  }
};

class MeshChangeLog {
 public:
  // O(1) amortised.
  void RecordAddedVertex(VertexId v) { Append(Kind::kAddVertex, Index(v)); }
  void RecordRemovedVertex(VertexId v) { Append(Kind::kRemoveVertex, Index(v)); }
  void RecordAddedTet(TetId t) { Append(Kind::kAddTet, Index(t)); }
  void RecordRemovedTet(TetId t, const TetVertices& corners) {
    Append(Kind::kRemoveTet, Index(t), corners);
  }
  void RecordMovedVertex(VertexId v) { Append(Kind::kMoveVertex, Index(v)); }

  // The current end of the log.
  ChangeMark Mark() const { return {first_kept_ + events_.size()}; }

  // Net changes from `since` to now. O(k log k) in the k events since the mark.
  // OUT_OF_RANGE if events from `since` on were discarded or `since` is in the future.
  absl::StatusOr<MeshChanges> ChangesSince(ChangeMark since) const;

  // Forgets the events before `mark` (no effect if already forgotten). O(events kept).
  void DiscardBefore(ChangeMark mark);

  // Events held in memory.
  std::size_t retained_events() const { return events_.size(); }

 private:
  enum class Kind : std::uint8_t { kAddVertex, kRemoveVertex, kAddTet, kRemoveTet, kMoveVertex };
  struct Event {
    Kind kind;
    std::uint32_t id;
    TetVertices corners;  // a removed tet's; unused otherwise
  };

  void Append(Kind kind, std::uint32_t id, const TetVertices& corners = {}) {
    events_.push_back({kind, id, corners});
  }

  std::uint64_t first_kept_ = 0;  // sequence number of events_[0]
  std::vector<Event> events_;
};

}  // namespace kerf::mesh
