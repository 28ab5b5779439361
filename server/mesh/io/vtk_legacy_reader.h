// VTK legacy files, ASCII, DATASET UNSTRUCTURED_GRID, in the classic CELLS layout and in the
// version 5.1 OFFSETS/CONNECTIVITY layout. Tetra cells (type 10) are read; lower-dimension
// cells are skipped; other volume cells are refused by type. Point and cell data are ignored.
#pragma once

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "mesh/io/tet_mesh_data.h"

namespace kerf::mesh {

absl::StatusOr<TetMeshData> ParseVtkLegacy(absl::string_view text, absl::string_view source);

}  // namespace kerf::mesh
