// Edges and faces of a tet mesh named by their vertices, whichever tet they are seen from.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "absl/hash/hash.h"
#include "mesh/mesh_ids.h"

namespace kerf::cut {

// An edge by its two vertices: the smaller id in the high half.
using EdgeKey = std::uint64_t;
inline EdgeKey MakeEdgeKey(mesh::VertexId a, mesh::VertexId b) {
  const std::uint64_t lo = std::min(mesh::Index(a), mesh::Index(b));
  const std::uint64_t hi = std::max(mesh::Index(a), mesh::Index(b));
  return lo << 32 | hi;
}
// The edge's vertices, the smaller id first.
inline std::array<mesh::VertexId, 2> EdgeEnds(EdgeKey key) {
  return {mesh::VertexId(static_cast<std::uint32_t>(key >> 32)),
          mesh::VertexId(static_cast<std::uint32_t>(key))};
}

// A face by its three vertices, smallest id first.
using FaceKey = std::array<mesh::VertexId, 3>;
inline FaceKey MakeFaceKey(mesh::VertexId a, mesh::VertexId b, mesh::VertexId c) {
  FaceKey key = {a, b, c};
  std::sort(key.begin(), key.end());
  return key;
}
struct FaceKeyHash {
  std::size_t operator()(const FaceKey& k) const {
    return absl::HashOf(mesh::Index(k[0]), mesh::Index(k[1]), mesh::Index(k[2]));
  }
};

}  // namespace kerf::cut
