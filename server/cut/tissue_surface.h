// The tissue's boundary as the mesh was given to the cutter: its vertices, edges and faces, by
// the ids of the tissue's own vertices (the origins a cut keeps naming them by). The crack's
// lips, which a cut adds to the boundary, are not part of it.
#pragma once

#include <Eigen/Core>
#include <array>
#include <span>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "cut/element_keys.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {

class TissueSurface {
 public:
  // The faces of one live tet of `mesh`, their edges and vertices. O(tets * star size).
  static TissueSurface Of(const mesh::TetMesh& mesh);

  bool HasVertex(mesh::VertexId v) const { return vertices_.contains(v); }
  bool HasEdge(mesh::VertexId a, mesh::VertexId b) const {
    return edges_.contains(MakeEdgeKey(a, b));
  }
  bool HasFace(const FaceKey& key) const { return faces_.contains(key); }
  // The surface's triangles at v (none for a vertex not on it).
  std::span<const std::array<mesh::VertexId, 3>> TrianglesAt(mesh::VertexId v) const {
    const auto it = triangles_.find(v);
    if (it == triangles_.end()) return {};
    return it->second;
  }
  // The outward normal at a vertex of the surface (its triangles' normals summed, weighted by
  // their areas) on the mesh's current positions; zero for a vertex not on it.
  Eigen::Vector3d Normal(const mesh::TetMesh& mesh, mesh::VertexId v) const;
  // Whether the segment p-q lies in the plane of a triangle of the surface at the edge a-b (its
  // ends within `tolerance`, m, of it), on the mesh's current positions: a blade lying there
  // slides along the surface. False for an edge not on the surface.
  bool SegmentOnFaceAtEdge(const mesh::TetMesh& mesh, mesh::VertexId a, mesh::VertexId b,
                           const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                           double tolerance) const;

 private:
  absl::flat_hash_set<mesh::VertexId> vertices_;
  absl::flat_hash_set<EdgeKey> edges_;
  absl::flat_hash_set<FaceKey, FaceKeyHash> faces_;
  // The surface's triangles at each vertex, ordered so the right-hand normal points out.
  absl::flat_hash_map<mesh::VertexId, std::vector<std::array<mesh::VertexId, 3>>> triangles_;
};

}  // namespace kerf::cut
