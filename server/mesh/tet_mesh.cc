#include "mesh/tet_mesh.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "base/check.h"
#include "geometry/tet_measures.h"

namespace kerf::mesh {
namespace {

// Each distinct corner once: a tet with a repeated vertex is in that vertex's star once.
bool IsFirstOccurrence(const TetVertices& tet, int corner) {
  for (int i = 0; i < corner; ++i) {
    if (tet[i] == tet[corner]) return false;
  }
  return true;
}

}  // namespace

bool TetHasVertex(const TetVertices& tet, VertexId v) {
  return tet[0] == v || tet[1] == v || tet[2] == v || tet[3] == v;
}

VertexId TetMesh::AddVertex(const Eigen::Vector3d& rest_position) {
  return AddVertex(rest_position, rest_position);
}

VertexId TetMesh::AddVertex(const Eigen::Vector3d& rest_position,
                            const Eigen::Vector3d& current_position) {
  // Either may be one of this mesh's own positions: copied before the lists grow.
  const Eigen::Vector3d rest = rest_position, current = current_position;
  VertexId v;
  if (free_vertices_.empty()) {
    v = static_cast<VertexId>(rest_.size());
    rest_.push_back(rest);
    current_.push_back(current);
    stars_.emplace_back();
    vertex_alive_.push_back(true);
  } else {
    v = static_cast<VertexId>(free_vertices_.back());
    free_vertices_.pop_back();
    rest_[Index(v)] = rest;
    current_[Index(v)] = current;
    vertex_alive_[Index(v)] = true;
  }
  ++vertex_count_;
  change_log_.RecordAddedVertex(v);
  return v;
}

absl::Status TetMesh::RemoveVertex(VertexId v) {
  if (!IsAlive(v)) return absl::NotFoundError(absl::StrCat("vertex ", Index(v), " is not alive"));
  if (!stars_[Index(v)].empty()) {
    return absl::FailedPreconditionError(
        absl::StrCat("vertex ", Index(v), " is used by ", stars_[Index(v)].size(), " tets"));
  }
  vertex_alive_[Index(v)] = false;
  stars_[Index(v)].clear();
  stars_[Index(v)].shrink_to_fit();  // release any heap storage
  --vertex_count_;
  waiting_.push_back({change_log_.Mark().sequence, Index(v), false});
  change_log_.RecordRemovedVertex(v);
  return absl::OkStatus();
}

absl::Status TetMesh::MoveVertex(VertexId v, const Eigen::Vector3d& rest_position,
                                 const Eigen::Vector3d& current_position) {
  if (!IsAlive(v)) return absl::NotFoundError(absl::StrCat("vertex ", Index(v), " is not alive"));
  rest_[Index(v)] = rest_position;
  current_[Index(v)] = current_position;
  change_log_.RecordMovedVertex(v);
  return absl::OkStatus();
}

absl::StatusOr<TetId> TetMesh::AddTet(const TetVertices& vertices) {
  for (const VertexId v : vertices) {
    if (!IsAlive(v)) {
      return absl::InvalidArgumentError(
          absl::StrCat("cannot add a tet on vertex ", Index(v), ": it is not alive"));
    }
  }
  TetId t;
  if (free_tets_.empty()) {
    t = static_cast<TetId>(tets_.size());
    tets_.push_back(vertices);
    tet_alive_.push_back(true);
  } else {
    t = static_cast<TetId>(free_tets_.back());
    free_tets_.pop_back();
    tets_[Index(t)] = vertices;
    tet_alive_[Index(t)] = true;
  }
  ++tet_count_;
  for (int i = 0; i < 4; ++i) {
    if (IsFirstOccurrence(vertices, i)) stars_[Index(vertices[i])].push_back(t);
  }
  change_log_.RecordAddedTet(t);
  return t;
}

absl::Status TetMesh::RemoveTet(TetId t) {
  if (!IsAlive(t)) return absl::NotFoundError(absl::StrCat("tet ", Index(t), " is not alive"));
  const TetVertices& vertices = tets_[Index(t)];
  for (int i = 0; i < 4; ++i) {
    if (!IsFirstOccurrence(vertices, i)) continue;
    Star& star = stars_[Index(vertices[i])];
    const auto it = std::find(star.begin(), star.end(), t);
    KERF_CHECK(it != star.end());
    *it = star.back();  // order in a star carries no meaning
    star.pop_back();
  }
  tet_alive_[Index(t)] = false;
  --tet_count_;
  waiting_.push_back({change_log_.Mark().sequence, Index(t), true});
  change_log_.RecordRemovedTet(t, vertices);
  return absl::OkStatus();
}

void TetMesh::ReuseIdsRemovedBefore(ChangeMark mark,
                                    const std::function<bool(VertexId)>& vertex_held,
                                    const std::function<bool(TetId)>& tet_held) {
  std::vector<Waiting> still;
  std::size_t i = 0;
  for (; i < waiting_.size() && waiting_[i].sequence < mark.sequence; ++i) {
    const Waiting& w = waiting_[i];
    KERF_CHECK(w.tet ? !tet_alive_[w.index] : !vertex_alive_[w.index]);
    const bool held =
        w.tet ? tet_held(static_cast<TetId>(w.index)) : vertex_held(static_cast<VertexId>(w.index));
    if (held) {
      still.push_back(w);
    } else {
      (w.tet ? free_tets_ : free_vertices_).push_back(w.index);
    }
  }
  still.insert(still.end(), waiting_.begin() + static_cast<std::ptrdiff_t>(i), waiting_.end());
  waiting_ = std::move(still);
  // The smallest free id goes first, whatever order the ids were removed in (a caller may remove
  // in a hash map's order): so the ids a history of changes issues depend on that history only.
  std::sort(free_vertices_.begin(), free_vertices_.end(), std::greater<>());
  std::sort(free_tets_.begin(), free_tets_.end(), std::greater<>());
}

TetMesh::TetList TetMesh::TetsAroundEdge(VertexId a, VertexId b) const {
  TetList result;
  for (const TetId t : TetsAround(a)) {
    if (TetHasVertex(tets_[Index(t)], b)) result.push_back(t);
  }
  return result;
}

TetMesh::TetList TetMesh::TetsAroundFace(VertexId a, VertexId b, VertexId c) const {
  TetList result;
  for (const TetId t : TetsAround(a)) {
    const TetVertices& tet = tets_[Index(t)];
    if (TetHasVertex(tet, b) && TetHasVertex(tet, c)) result.push_back(t);
  }
  return result;
}

double RestVolume(const TetMesh& mesh, TetId t) {
  const TetVertices& v = mesh.tet(t);
  return geometry::SignedVolume(mesh.rest_position(v[0]), mesh.rest_position(v[1]),
                                mesh.rest_position(v[2]), mesh.rest_position(v[3]));
}

double CurrentVolume(const TetMesh& mesh, TetId t) {
  const TetVertices& v = mesh.tet(t);
  return geometry::SignedVolume(mesh.current_position(v[0]), mesh.current_position(v[1]),
                                mesh.current_position(v[2]), mesh.current_position(v[3]));
}

}  // namespace kerf::mesh
