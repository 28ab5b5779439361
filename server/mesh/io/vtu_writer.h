// Writes a mesh as a VTK XML unstructured grid (.vtu) that ParaView opens: current positions
// as the points, one tetra cell per live tet in id order, arrays as base64 binary, Float64
// and Int64, with UInt64 headers.
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "mesh/tet_mesh.h"

namespace kerf::mesh {

// A named array with one tuple per live vertex (point data) or live tet (cell data), in
// increasing id order.
struct VtuDataArray {
  std::string name;
  int components = 1;
  std::variant<std::vector<double>, std::vector<std::int64_t>> values;
};

struct VtuExtraArrays {
  std::vector<VtuDataArray> point_data;
  std::vector<VtuDataArray> cell_data;
};

// The point array "rest_position": each live vertex's rest position.
VtuDataArray RestPositionArray(const TetMesh& mesh);

// The whole file's text. Array sizes must match the live counts times components (asserted).
std::string FormatVtu(const TetMesh& mesh, const VtuExtraArrays& extra = {});

}  // namespace kerf::mesh
