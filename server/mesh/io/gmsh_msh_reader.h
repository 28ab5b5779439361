// Gmsh MSH files, ASCII: version 1 ($NOD/$ELM), 2 ($Nodes/$Elements) and 4.0/4.1 (entity
// blocks). Linear tetrahedra (element type 4) are read; points, lines and surface elements
// (triangles, quads and their higher-order kinds) are skipped; any other volume element is
// refused by type. Binary MSH is refused.
#pragma once

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "mesh/io/tet_mesh_data.h"

namespace kerf::mesh {

// `source` names the text in error messages (usually the file name).
absl::StatusOr<TetMeshData> ParseGmshMsh(absl::string_view text, absl::string_view source);

}  // namespace kerf::mesh
