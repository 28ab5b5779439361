#include "mesh/boundary_surface.h"

namespace kerf::mesh {

std::vector<BoundaryTriangle> ExtractBoundarySurface(const TetMesh& mesh) {
  std::vector<BoundaryTriangle> triangles;
  for (const TetId t : mesh.tets()) {
    const TetVertices& v = mesh.tet(t);
    for (int corner = 0; corner < 4; ++corner) {
      const auto& face = kTetFaces[corner];
      const std::array<VertexId, 3> tri = {v[face[0]], v[face[1]], v[face[2]]};
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;
      if (mesh.TetsAroundFace(tri[0], tri[1], tri[2]).size() == 1) {
        triangles.push_back({tri, t, corner});
      }
    }
  }
  return triangles;
}

}  // namespace kerf::mesh
