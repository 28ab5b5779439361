// The boundary surface of a tet mesh: the faces that belong to exactly one tet.
#pragma once

#include <array>
#include <vector>

#include "mesh/tet_mesh.h"

namespace kerf::mesh {

struct BoundaryTriangle {
  // Ordered so that the right-hand normal points out of the tet (for a positively
  // oriented tet), i.e. out of the body.
  std::array<VertexId, 3> vertices;
  TetId tet;
  int opposite_corner;  // local index (0..3) in the tet of the corner not on this face
};

// Triangles of faces with exactly one live tet, ordered by tet id then corner. A face of a
// repeated-vertex tet is skipped. O(tets * log(star size)).
std::vector<BoundaryTriangle> ExtractBoundarySurface(const TetMesh& mesh);

}  // namespace kerf::mesh
