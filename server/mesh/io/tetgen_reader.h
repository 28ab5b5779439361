// TetGen .node and .ele files (ASCII, '#' comments). Points may carry attributes and a
// boundary marker; tets must have 4 corners (second-order, 10-corner tets are refused).
#pragma once

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "mesh/io/tet_mesh_data.h"

namespace kerf::mesh {

absl::StatusOr<TetMeshData> ParseTetGen(absl::string_view node_text, absl::string_view node_source,
                                        absl::string_view ele_text, absl::string_view ele_source);

}  // namespace kerf::mesh
