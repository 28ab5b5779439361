// Writes a mesh as Gmsh MSH 4.1 ASCII: one volume entity, rest positions, node tags equal to
// the stable vertex ids plus one (MSH tags start at 1), one element per live tet in id order.
// Numbers are written in their shortest exact form, so reading the file back gives the same
// doubles.
#pragma once

#include <string>

#include "mesh/tet_mesh.h"

namespace kerf::mesh {

std::string FormatGmshMsh4(const TetMesh& mesh);

}  // namespace kerf::mesh
