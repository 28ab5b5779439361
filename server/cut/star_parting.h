// Parting the vertices a crack separates. The tets around a vertex, joined through their faces
// at it that are not crack faces, form parts; where there is more than one, the largest part
// keeps the vertex and each other part gets a copy (same rest and current position), so the
// crack opens there. A vertex on the crack's front (the crack ends at it) has one part and stays
// whole. Parting one vertex never joins or separates the parts of another: two tets at v in
// different parts share only crack faces at v.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "absl/container/flat_hash_set.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {

// A face by its three vertices, smallest id first.
using FaceKey = std::array<mesh::VertexId, 3>;
FaceKey MakeFaceKey(mesh::VertexId a, mesh::VertexId b, mesh::VertexId c);
struct FaceKeyHash {
  std::size_t operator()(const FaceKey& k) const {
    return absl::HashOf(mesh::Index(k[0]), mesh::Index(k[1]), mesh::Index(k[2]));
  }
};
using CrackFaceSet = absl::flat_hash_set<FaceKey, FaceKeyHash>;

struct VertexCopy {
  mesh::VertexId copy;
  mesh::VertexId from;
};

struct Parting {
  std::vector<VertexCopy> copies;
  std::vector<std::pair<mesh::TetId, mesh::TetId>> replaced;  // old tet, the tet now in its place
};

// Parts each of `vertices` (live) whose parts are more than one. `crack` gains the keys of the
// crack faces renamed by a copy. O(stars of the vertices).
Parting PartVertices(mesh::TetMesh* mesh, const std::vector<mesh::VertexId>& vertices,
                     CrackFaceSet* crack);

}  // namespace kerf::cut
