#include "mesh/boundary_surface.h"

#include <algorithm>
#include <tuple>

namespace kerf::mesh {

std::vector<BoundaryTriangle> ExtractBoundarySurface(const TetMesh& mesh) {
  // Each face is looked at from the star of its smallest vertex: the faces there that no other
  // tet of the star shares are the boundary's. Each tet is read once for each of its corners.
  struct FaceAt {
    VertexId b, c;  // the face's other two vertices, b < c
    TetId tet;
    int corner;  // the tet's corner opposite the face
  };
  std::vector<BoundaryTriangle> triangles;
  std::vector<FaceAt> faces;
  for (const VertexId a : mesh.vertices()) {
    faces.clear();
    for (const TetId t : mesh.TetsAround(a)) {
      const TetVertices& v = mesh.tet(t);
      for (int corner = 0; corner < 4; ++corner) {
        if (v[corner] == a) continue;  // the face opposite a does not hold it
        // The face's two vertices besides a (one of them a itself where the tet repeats it).
        const auto& face = kTetFaces[corner];
        VertexId b = a, c = a;
        for (const int k : face) {
          if (v[k] == a) continue;
          (b == a ? b : c) = v[k];
        }
        if (b == a || c == a || b == c) continue;  // a repeated vertex
        if (c < b) std::swap(b, c);
        if (b < a) continue;  // looked at from the star of its smallest vertex
        faces.push_back({b, c, t, corner});
      }
    }
    std::sort(faces.begin(), faces.end(), [](const FaceAt& x, const FaceAt& y) {
      return std::tie(x.b, x.c) < std::tie(y.b, y.c);
    });
    for (std::size_t i = 0; i < faces.size();) {
      std::size_t j = i + 1;
      while (j < faces.size() && faces[j].b == faces[i].b && faces[j].c == faces[i].c) ++j;
      if (j == i + 1) {
        const TetVertices& v = mesh.tet(faces[i].tet);
        const auto& face = kTetFaces[faces[i].corner];
        triangles.push_back({{v[face[0]], v[face[1]], v[face[2]]}, faces[i].tet, faces[i].corner});
      }
      i = j;
    }
  }
  std::sort(triangles.begin(), triangles.end(),
            [](const BoundaryTriangle& x, const BoundaryTriangle& y) {
              return std::tie(x.tet, x.opposite_corner) < std::tie(y.tet, y.opposite_corner);
            });
  return triangles;
}

}  // namespace kerf::mesh
