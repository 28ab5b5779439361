#include "cut/star_parting.h"

#include <algorithm>
#include <numeric>

#include "base/check.h"

namespace kerf::cut {
namespace {

using mesh::TetId;
using mesh::VertexId;

constexpr VertexId kNone{0xffffffffu};

int Root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

std::vector<VertexId> VertexParting::Ids(VertexId origin) const {
  std::vector<VertexId> ids = {origin};
  if (const auto it = copies_.find(origin); it != copies_.end()) {
    ids.insert(ids.end(), it->second.begin(), it->second.end());
  }
  return ids;
}

std::vector<TetId> VertexParting::TetsAround(const mesh::TetMesh& mesh, VertexId origin) const {
  std::vector<TetId> tets;
  for (const VertexId v : Ids(origin)) {
    if (mesh.IsAlive(v))
      tets.insert(tets.end(), mesh.TetsAround(v).begin(), mesh.TetsAround(v).end());
  }
  std::sort(tets.begin(), tets.end());
  return tets;
}

PartingChanges VertexParting::Repart(mesh::TetMesh* mesh, const std::vector<VertexId>& origins,
                                     const std::function<bool(const FaceKey&)>& on_crack,
                                     const std::function<bool(TetId)>& fresh) {
  PartingChanges changes;
  absl::flat_hash_set<TetId> renamed_fresh;  // fresh tets rewritten for an earlier origin
  const auto is_fresh = [&](TetId t) { return (fresh && fresh(t)) || renamed_fresh.contains(t); };
  std::vector<VertexId> todo;
  for (const VertexId v : origins) todo.push_back(Origin(v));
  std::sort(todo.begin(), todo.end());
  todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
  for (const VertexId o : todo) {
    if (!mesh->IsAlive(o)) continue;
    const std::vector<TetId> star = TetsAround(*mesh, o);
    if (star.empty()) continue;
    const std::vector<VertexId> ids = Ids(o);
    const std::vector<std::vector<int>> parts = PartsOfStar(*mesh, o, star, on_crack);
    const std::vector<VertexId> assigned = IdsOfParts(mesh, o, star, parts, is_fresh, &changes);
    for (std::size_t p = 0; p < parts.size(); ++p) {
      for (const int i : parts[p]) {
        const VertexId now = IdIn(*mesh, star[i], o);
        if (now == assigned[p]) continue;
        mesh::TetVertices corners = mesh->tet(star[i]);
        std::replace(corners.begin(), corners.end(), now, assigned[p]);
        KERF_CHECK(mesh->RemoveTet(star[i]).ok());
        const absl::StatusOr<TetId> added = mesh->AddTet(corners);
        KERF_CHECK(added.ok());
        if (is_fresh(star[i])) renamed_fresh.insert(*added);
        changes.replaced.push_back({star[i], *added});
      }
    }
    for (const VertexId id : ids) {
      if (id == o || !mesh->IsAlive(id) ||
          std::find(assigned.begin(), assigned.end(), id) != assigned.end()) {
        continue;
      }
      KERF_CHECK(mesh->TetsAround(id).empty());
      KERF_CHECK(mesh->RemoveVertex(id).ok());
      changes.removed.push_back(id);
      std::vector<VertexId>& copies = copies_[o];
      copies.erase(std::find(copies.begin(), copies.end(), id));
      origin_[mesh::Index(id)] = kNoOrigin;  // no copy any more: its id may name a new vertex
    }
  }
  return changes;
}

void VertexParting::AddNamedVertices(absl::flat_hash_set<VertexId>* named) const {
  for (const auto& [origin, copies] : copies_) {
    named->insert(origin);
    named->insert(copies.begin(), copies.end());
  }
}

VertexId VertexParting::IdIn(const mesh::TetMesh& mesh, TetId t, VertexId origin) const {
  for (const VertexId v : mesh.tet(t)) {
    if (Origin(v) == origin) return v;
  }
  KERF_CHECK(false);
  return origin;
}

std::vector<std::vector<int>> VertexParting::PartsOfStar(
    const mesh::TetMesh& mesh, VertexId o, const std::vector<TetId>& star,
    const std::function<bool(const FaceKey&)>& on_crack) const {
  // Tets joined through faces at o that are not on the crack.
  std::vector<int> parent(star.size());
  std::iota(parent.begin(), parent.end(), 0);
  absl::flat_hash_map<FaceKey, int, FaceKeyHash> first_with;
  for (int i = 0; i < static_cast<int>(star.size()); ++i) {
    const mesh::TetVertices& t = mesh.tet(star[i]);
    for (const auto& f : mesh::kTetFaces) {
      const FaceKey key = OriginKey(t[f[0]], t[f[1]], t[f[2]]);
      if (std::find(key.begin(), key.end(), o) == key.end() || on_crack(key)) continue;
      const auto [it, inserted] = first_with.try_emplace(key, i);
      if (!inserted) parent[Root(parent, i)] = Root(parent, it->second);
    }
  }
  absl::flat_hash_map<int, std::vector<int>> by_root;
  for (int i = 0; i < static_cast<int>(star.size()); ++i) by_root[Root(parent, i)].push_back(i);
  std::vector<std::vector<int>> parts;
  for (auto& [root, members] : by_root) parts.push_back(std::move(members));
  // Larger parts first; among equals, the one with the lower first tet.
  std::sort(parts.begin(), parts.end(), [&](const auto& a, const auto& b) {
    return a.size() != b.size() ? a.size() > b.size() : star[a.front()] < star[b.front()];
  });
  return parts;
}

std::vector<VertexId> VertexParting::IdsOfParts(mesh::TetMesh* mesh, VertexId o,
                                                const std::vector<TetId>& star,
                                                const std::vector<std::vector<int>>& parts,
                                                const std::function<bool(TetId)>& is_fresh,
                                                PartingChanges* changes) {
  // Each part keeps the id most of its tets use (larger parts choose first), so no tet moves
  // unless parts merge. A part left with none takes the origin if no part kept it, else a new
  // copy, either starting where its tets had the vertex.
  std::vector<VertexId> assigned(parts.size(), kNone), had(parts.size(), kNone);
  absl::flat_hash_set<VertexId> taken;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    absl::flat_hash_map<VertexId, int> uses;
    for (const int i : parts[p]) {
      if (!is_fresh(star[i])) ++uses[IdIn(*mesh, star[i], o)];
    }
    if (uses.empty()) {
      for (const int i : parts[p]) ++uses[IdIn(*mesh, star[i], o)];
    }
    int most = 0, most_free = 0;
    for (const auto& [id, n] : uses) {
      if (n > most || (n == most && id < had[p])) most = n, had[p] = id;
      if (!taken.contains(id) && (n > most_free || (n == most_free && id < assigned[p]))) {
        most_free = n;
        assigned[p] = id;
      }
    }
    if (assigned[p] != kNone) taken.insert(assigned[p]);
  }
  for (std::size_t p = 0; p < parts.size(); ++p) {
    if (assigned[p] != kNone) continue;
    if (!taken.contains(o)) {
      assigned[p] = o;
      KERF_CHECK(
          mesh->MoveVertex(o, mesh->rest_position(had[p]), mesh->current_position(had[p])).ok());
      changes->made.push_back({o, had[p]});
    } else {
      assigned[p] = mesh->AddVertex(mesh->rest_position(had[p]), mesh->current_position(had[p]));
      const std::uint32_t i = mesh::Index(assigned[p]);
      if (origin_.size() <= i) origin_.resize(i + 1, kNoOrigin);
      origin_[i] = o;
      copies_[o].push_back(assigned[p]);
      changes->made.push_back({assigned[p], had[p]});
    }
    taken.insert(assigned[p]);
  }
  if (!taken.contains(o)) {
    // Every part kept a copy: the largest takes the origin (the key the crack names it by) in
    // its copy's place, and the copy goes.
    const VertexId copy = assigned[0];
    KERF_CHECK(mesh->MoveVertex(o, mesh->rest_position(copy), mesh->current_position(copy)).ok());
    changes->made.push_back({o, copy});
    assigned[0] = o;
  }
  return assigned;
}

bool VertexParting::RemoveIfUnused(mesh::TetMesh* mesh, VertexId origin) {
  const std::vector<VertexId> ids = Ids(origin);
  for (const VertexId v : ids) {
    if (mesh->IsAlive(v) && !mesh->TetsAround(v).empty()) return false;
  }
  for (const VertexId v : ids) {
    if (mesh->IsAlive(v)) KERF_CHECK(mesh->RemoveVertex(v).ok());
    if (mesh::Index(v) < origin_.size()) origin_[mesh::Index(v)] = kNoOrigin;
  }
  copies_.erase(origin);
  return true;
}

}  // namespace kerf::cut
