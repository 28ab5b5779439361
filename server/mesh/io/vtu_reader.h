// VTK XML unstructured grids (.vtu) with inline data arrays, format "ascii" or "binary"
// (base64, UInt32 or UInt64 headers, either byte order). Compressed and appended data are
// refused. Tetra cells are read, lower-dimension cells skipped, other volume cells refused.
#pragma once

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "mesh/io/tet_mesh_data.h"

namespace kerf::mesh {

absl::StatusOr<TetMeshData> ParseVtu(absl::string_view text, absl::string_view source);

}  // namespace kerf::mesh
