// The crack a cut opened in a tet mesh.
//
// Cut vertices come in copies at the same rest position (one per side of the crack), so a
// face on the crack has a twin: another face in one tet with the same three rest positions.
// (A crack crossed again by a later cut may be tiled anew on one side; those faces have no twin
// and are not counted. Conformity is checked by mesh::CheckOriginalFacesTiled.)
#pragma once

#include "mesh/tet_mesh.h"

namespace kerf::mesh {

// Half the rest area of the boundary faces that have a twin, m^2. O(tets * star size).
double MeasureCrackArea(const TetMesh& mesh);

}  // namespace kerf::mesh
