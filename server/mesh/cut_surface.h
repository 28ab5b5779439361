// The surface of a cut mesh split into what was there before and the crack the cut opened.
//
// Cut vertices come in copies at the same rest position (one per side of the crack), so a
// face on the crack has a twin: another face in one tet with the same three rest positions.
// The other faces in one tet are the original surface, so their area equals the original
// surface's, unless a later cut crossed a crack and tiled one of its sides anew (those faces
// then have no twin). Conformity is checked by mesh::CheckOriginalFacesTiled.
#pragma once

#include <cstddef>

#include "mesh/tet_mesh.h"

namespace kerf::mesh {

struct CutSurface {
  double surface_area = 0;  // m^2, faces in one tet without a twin (rest positions)
  double crack_area = 0;    // m^2, the crack opened: half the area of the twinned faces
  std::size_t crack_faces = 0;
};

// O(tets * star size).
CutSurface MeasureCutSurface(const TetMesh& mesh);

}  // namespace kerf::mesh
