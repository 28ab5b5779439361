// VTK cell type numbers shared by the legacy and XML readers.
#pragma once

#include <cstdint>

namespace kerf::mesh::internal {

inline constexpr std::int64_t kVtkTetra = 10;

// Vertices, lines, triangles, polygons, pixels, quads and their quadratic kinds: skipped
// when reading a volume mesh.
inline bool IsLowerDimensionVtkCell(std::int64_t type) {
  return (type >= 1 && type <= 9) || type == 21 || type == 22 || type == 23 || type == 28 ||
         type == 30 || type == 34 || type == 35 || type == 36 || type == 37;
}

}  // namespace kerf::mesh::internal
