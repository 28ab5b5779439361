#include "cut/star_parting.h"

#include <algorithm>
#include <numeric>

#include "absl/container/flat_hash_map.h"
#include "base/check.h"

namespace kerf::cut {
namespace {

using mesh::Index;
using mesh::TetId;
using mesh::VertexId;

int Root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

FaceKey MakeFaceKey(VertexId a, VertexId b, VertexId c) {
  FaceKey key = {a, b, c};
  std::sort(key.begin(), key.end());
  return key;
}

Parting PartVertices(mesh::TetMesh* mesh, const std::vector<VertexId>& vertices,
                     CrackFaceSet* crack) {
  Parting parting;
  for (const VertexId v : vertices) {
    if (!mesh->IsAlive(v)) continue;
    const std::vector<TetId> star(mesh->TetsAround(v).begin(), mesh->TetsAround(v).end());
    // Union of the tets through each face at v that two of them share and is not on the crack.
    std::vector<int> parent(star.size());
    std::iota(parent.begin(), parent.end(), 0);
    absl::flat_hash_map<FaceKey, int, FaceKeyHash> first_with;
    for (int i = 0; i < static_cast<int>(star.size()); ++i) {
      const mesh::TetVertices& t = mesh->tet(star[i]);
      for (const auto& f : mesh::kTetFaces) {
        const FaceKey key = MakeFaceKey(t[f[0]], t[f[1]], t[f[2]]);
        if (std::find(key.begin(), key.end(), v) == key.end() || crack->contains(key)) continue;
        const auto [it, inserted] = first_with.try_emplace(key, i);
        if (!inserted) parent[Root(parent, i)] = Root(parent, it->second);
      }
    }
    absl::flat_hash_map<int, std::vector<TetId>> parts;
    for (int i = 0; i < static_cast<int>(star.size()); ++i) {
      parts[Root(parent, i)].push_back(star[i]);
    }
    if (parts.size() < 2) continue;
    std::vector<std::vector<TetId>> ordered;
    for (auto& [root, tets] : parts) {
      std::sort(tets.begin(), tets.end());
      ordered.push_back(std::move(tets));
    }
    // The largest part keeps v (the lowest tet id breaks ties, so the result is deterministic).
    std::sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) {
      return a.size() != b.size() ? a.size() > b.size() : a.front() < b.front();
    });
    for (std::size_t p = 1; p < ordered.size(); ++p) {
      const VertexId copy = mesh->AddVertex(mesh->rest_position(v), mesh->current_position(v));
      parting.copies.push_back({copy, v});
      for (const TetId t : ordered[p]) {
        mesh::TetVertices corners = mesh->tet(t);
        for (const auto& f : mesh::kTetFaces) {
          const FaceKey key = MakeFaceKey(corners[f[0]], corners[f[1]], corners[f[2]]);
          if (!crack->contains(key)) continue;
          FaceKey renamed = key;
          std::replace(renamed.begin(), renamed.end(), v, copy);
          if (renamed != key) crack->insert(MakeFaceKey(renamed[0], renamed[1], renamed[2]));
        }
        std::replace(corners.begin(), corners.end(), v, copy);
        KERF_CHECK(mesh->RemoveTet(t).ok());
        const absl::StatusOr<TetId> added = mesh->AddTet(corners);
        KERF_CHECK(added.ok());
        parting.replaced.push_back({t, *added});
      }
    }
  }
  return parting;
}

}  // namespace kerf::cut
