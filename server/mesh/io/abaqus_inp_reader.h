// The mesh in an Abaqus/CalculiX input deck: *NODE blocks (id, x, y, z) and *ELEMENT blocks
// of TYPE=C3D4 (id, four node ids). Other element types are refused by name; all other
// keywords (materials, sets, steps) are not part of the mesh and are passed over here.
#pragma once

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "mesh/io/tet_mesh_data.h"

namespace kerf::mesh {

absl::StatusOr<TetMeshData> ParseAbaqusInpMesh(absl::string_view text, absl::string_view source);

}  // namespace kerf::mesh
