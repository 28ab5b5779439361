// A tetrahedral mesh with rest and current positions, stable ids and vertex stars.
//
// Connectivity and geometry: each vertex has a rest position (the undeformed shape the
// elastic model measures strain from) and a current position (the deformed shape). Each tet
// is four vertex ids.
//
// Ids: vertices and tets get ids 0, 1, 2, ... in order of creation, so per-element data can live
// in arrays indexed by Index(id). A removed element leaves a dead slot that keeps its last
// positions until its owner releases the id (ReuseIdsRemovedBefore, once every reader that needs
// the old data has read past the removal); a later addition then takes the released id again.
// So memory follows the elements alive and those waiting, not every element ever created; and
// readers of the change log see a reused id as removed and added.
//
// Adjacency: the mesh stores the star of every vertex (the tets that use it). The tets
// around an edge or a face are the tets in the star of one of its vertices that use the
// others, so they cost O(star size) to find and never go stale.
//
// Every addition and removal is recorded in change_log().
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <iterator>
#include <span>
#include <vector>

#include "absl/container/inlined_vector.h"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "base/check.h"
#include "mesh/mesh_change_log.h"
#include "mesh/mesh_ids.h"

namespace kerf::mesh {

// The live ids among 0 .. alive.size()-1, in increasing order; skips dead slots.
template <typename Id>
class LiveIdRange {
 public:
  class Iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = Id;
    using difference_type = std::ptrdiff_t;
    using pointer = const Id*;
    using reference = Id;

    Iterator() = default;
    Iterator(const std::vector<bool>* alive, std::uint32_t index) : alive_(alive), index_(index) {
      SkipDead();
    }
    Id operator*() const { return static_cast<Id>(index_); }
    Iterator& operator++() {
      ++index_;
      SkipDead();
      return *this;
    }
    Iterator operator++(int) {
      Iterator old = *this;
      ++*this;
      return old;
    }
    friend bool operator==(const Iterator& a, const Iterator& b) { return a.index_ == b.index_; }

   private:
    void SkipDead() {
      while (index_ < alive_->size() && !(*alive_)[index_]) ++index_;
    }
    const std::vector<bool>* alive_ = nullptr;
    std::uint32_t index_ = 0;
  };

  explicit LiveIdRange(const std::vector<bool>& alive) : alive_(&alive) {}
  Iterator begin() const { return Iterator(alive_, 0); }
  Iterator end() const { return Iterator(alive_, static_cast<std::uint32_t>(alive_->size())); }

 private:
  const std::vector<bool>* alive_;
};

class TetMesh {
 public:
  // Tets around one vertex; a lattice vertex has at most 24.
  using Star = absl::InlinedVector<TetId, 24>;
  using TetList = absl::InlinedVector<TetId, 8>;

  TetMesh() = default;

  // --- Vertices ------------------------------------------------------------------------------

  // Adds a vertex at rest; its current position starts equal to the rest position. O(1).
  VertexId AddVertex(const Eigen::Vector3d& rest_position);
  VertexId AddVertex(const Eigen::Vector3d& rest_position, const Eigen::Vector3d& current_position);

  // Removes a vertex that no tet uses. NOT_FOUND if it is not alive; FAILED_PRECONDITION if a
  // tet still uses it. O(1).
  absl::Status RemoveVertex(VertexId v);

  // Gives a live vertex new rest and current positions (a temporary point of a progressive cut
  // following the blade), recorded as a move. NOT_FOUND if it is not alive. O(1).
  absl::Status MoveVertex(VertexId v, const Eigen::Vector3d& rest_position,
                          const Eigen::Vector3d& current_position);

  bool IsAlive(VertexId v) const {
    return Index(v) < vertex_alive_.size() && vertex_alive_[Index(v)];
  }
  std::size_t vertex_count() const { return vertex_count_; }
  // One past the largest vertex index ever issued: the size per-vertex arrays need.
  std::uint32_t vertex_index_bound() const { return static_cast<std::uint32_t>(rest_.size()); }
  LiveIdRange<VertexId> vertices() const { return LiveIdRange<VertexId>(vertex_alive_); }

  // Positions of a live vertex (checked).
  const Eigen::Vector3d& rest_position(VertexId v) const {
    KERF_CHECK(IsAlive(v));
    return rest_[Index(v)];
  }
  const Eigen::Vector3d& current_position(VertexId v) const {
    KERF_CHECK(IsAlive(v));
    return current_[Index(v)];
  }
  void set_current_position(VertexId v, const Eigen::Vector3d& position) {
    KERF_CHECK(IsAlive(v));
    current_[Index(v)] = position;
  }

  // All positions indexed by Index(id). A removed vertex's slot keeps its last positions until
  // its id is reused.
  std::span<const Eigen::Vector3d> rest_positions() const { return rest_; }
  std::span<const Eigen::Vector3d> current_positions() const { return current_; }
  std::span<Eigen::Vector3d> mutable_current_positions() { return current_; }

  // --- Tets --------------------------------------------------------------------------------

  // Adds a tet on live vertices. INVALID_ARGUMENT if a vertex is not alive. Geometric and
  // topological defects (a repeated vertex, a flat or inverted tet, a face in three tets) are
  // accepted, so that a defective file can be loaded and FindMeshDefects can report them.
  // O(1) amortised.
  absl::StatusOr<TetId> AddTet(const TetVertices& vertices);

  // Removes a live tet; NOT_FOUND otherwise. Its vertices stay. O(star sizes).
  absl::Status RemoveTet(TetId t);

  bool IsAlive(TetId t) const { return Index(t) < tet_alive_.size() && tet_alive_[Index(t)]; }
  std::size_t tet_count() const { return tet_count_; }
  std::uint32_t tet_index_bound() const { return static_cast<std::uint32_t>(tets_.size()); }
  LiveIdRange<TetId> tets() const { return LiveIdRange<TetId>(tet_alive_); }

  // The corners of a live tet (checked).
  const TetVertices& tet(TetId t) const {
    KERF_CHECK(IsAlive(t));
    return tets_[Index(t)];
  }

  // --- Adjacency -----------------------------------------------------------------------------

  // The live tets using vertex v, in no particular order. O(1).
  std::span<const TetId> TetsAround(VertexId v) const {
    KERF_CHECK(IsAlive(v));
    const Star& star = stars_[Index(v)];
    return {star.data(), star.size()};
  }

  // The live tets having both a and b as corners. O(star of a).
  TetList TetsAroundEdge(VertexId a, VertexId b) const;

  // The live tets having a, b and c as corners: at most two in a valid mesh. O(star of a).
  TetList TetsAroundFace(VertexId a, VertexId b, VertexId c) const;

  // --- Changes -------------------------------------------------------------------------------

  const MeshChangeLog& change_log() const { return change_log_; }
  // Forgets the changes before `mark`, which every reader of the log has passed (a reader asking
  // for them gets OUT_OF_RANGE). O(changes kept).
  void DiscardChangesBefore(ChangeMark mark) { change_log_.DiscardBefore(mark); }

  // --- Reuse of ids --------------------------------------------------------------------------

  // Frees for reuse the ids of the vertices and tets removed before `mark`, except those the
  // predicates hold (a caller still naming them); held ids wait for a later call. Whoever calls
  // it promises that no reader still needs a freed slot's last positions. The next additions take
  // the freed ids, smallest first. O(ids waiting) predicate calls and O(F log F) in the F free.
  void ReuseIdsRemovedBefore(ChangeMark mark, const std::function<bool(VertexId)>& vertex_held,
                             const std::function<bool(TetId)>& tet_held);
  // Removed ids not yet freed, and freed ids not yet taken again.
  std::size_t ids_waiting() const { return waiting_.size(); }
  std::size_t ids_free() const { return free_vertices_.size() + free_tets_.size(); }

 private:
  std::vector<Eigen::Vector3d> rest_;
  std::vector<Eigen::Vector3d> current_;
  std::vector<Star> stars_;
  std::vector<bool> vertex_alive_;
  std::size_t vertex_count_ = 0;

  std::vector<TetVertices> tets_;
  std::vector<bool> tet_alive_;
  std::size_t tet_count_ = 0;

  MeshChangeLog change_log_;
  // Removed ids in order of removal, with the change log's sequence number of their removal.
  struct Waiting {
    std::uint64_t sequence;
    std::uint32_t index;
    bool tet;
  };
  std::vector<Waiting> waiting_;
  std::vector<std::uint32_t> free_vertices_;
  std::vector<std::uint32_t> free_tets_;
};

// True if the tet has vertex v as a corner.
bool TetHasVertex(const TetVertices& tet, VertexId v);

// The rest and current signed volumes of a live tet.
double RestVolume(const TetMesh& mesh, TetId t);
double CurrentVolume(const TetMesh& mesh, TetId t);

}  // namespace kerf::mesh
