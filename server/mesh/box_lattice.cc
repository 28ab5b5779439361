#include "mesh/box_lattice.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "base/check.h"
#include "geometry/tet_measures.h"

namespace kerf::mesh {
namespace {

constexpr int kMaxCellsPerAxis = 1024;

// The Z-order (Morton) code of grid point (i, j, k): the bits of the three interleaved.
std::uint64_t MortonCode(int i, int j, int k) {
  std::uint64_t code = 0;
  for (int bit = 0; bit < 11; ++bit) {
    code |= (std::uint64_t{(static_cast<unsigned>(i) >> bit) & 1u} << (3 * bit)) |
            (std::uint64_t{(static_cast<unsigned>(j) >> bit) & 1u} << (3 * bit + 1)) |
            (std::uint64_t{(static_cast<unsigned>(k) >> bit) & 1u} << (3 * bit + 2));
  }
  return code;
}

// The points of an nx x ny x nz grid in Z-order.
std::vector<std::array<int, 3>> ZOrder(int nx, int ny, int nz) {
  std::vector<std::array<int, 3>> points;
  points.reserve(static_cast<std::size_t>(nx) * ny * nz);
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) points.push_back({i, j, k});
    }
  }
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
    return MortonCode(a[0], a[1], a[2]) < MortonCode(b[0], b[1], b[2]);
  });
  return points;
}

absl::Status CheckCount(const char* name, int count) {
  if (count < 1 || count > kMaxCellsPerAxis) {
    return absl::InvalidArgumentError(
        absl::StrCat(name, " must be in [1, ", kMaxCellsPerAxis, "], got ", count));
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<TetMesh> MakeBoxLattice(const BoxLatticeSpec& spec) {
  if (auto s = CheckCount("cells_x", spec.cells_x); !s.ok()) return s;
  if (auto s = CheckCount("cells_y", spec.cells_y); !s.ok()) return s;
  if (auto s = CheckCount("cells_z", spec.cells_z); !s.ok()) return s;
  const std::array<int, 3> cells = {spec.cells_x, spec.cells_y, spec.cells_z};
  Eigen::Vector3d size = spec.size;
  if (size.isZero()) size = Eigen::Vector3d(cells[0], cells[1], cells[2]);
  for (int axis = 0; axis < 3; ++axis) {
    if (!std::isfinite(size[axis]) || size[axis] <= 0) {
      return absl::InvalidArgumentError(
          absl::StrCat("size ", absl::string_view("xyz").substr(axis, 1),
                       " must be positive and finite, got ", size[axis]));
    }
  }
  const Eigen::Vector3d step(size[0] / cells[0], size[1] / cells[1], size[2] / cells[2]);
  const int nx = cells[0] + 1, ny = cells[1] + 1, nz = cells[2] + 1;
  const auto point_index = [&](int i, int j, int k) {
    const auto size_of = [](int n) { return static_cast<std::size_t>(n); };
    return size_of(i) + size_of(nx) * (size_of(j) + size_of(ny) * size_of(k));
  };

  TetMesh mesh;
  std::vector<VertexId> vertex_of_point(static_cast<std::size_t>(nx) * ny * nz);
  for (const auto& [i, j, k] : ZOrder(nx, ny, nz)) {
    // The last layer sits exactly on the box's far face.
    vertex_of_point[point_index(i, j, k)] = mesh.AddVertex(Eigen::Vector3d(
        i == cells[0] ? size[0] : i * step[0], j == cells[1] ? size[1] : j * step[1],
        k == cells[2] ? size[2] : k * step[2]));
  }
  auto vertex_at = [&](int i, int j, int k) { return vertex_of_point[point_index(i, j, k)]; };

  // The six paths from corner (0,0,0) to (1,1,1) along cube edges, one per axis order; each
  // path's four corners form a tet. Odd permutations give negative orientation.
  constexpr std::array<std::array<int, 3>, 6> kAxisOrders = {
      {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}}};
  for (const auto& [i, j, k] : ZOrder(cells[0], cells[1], cells[2])) {
    for (std::size_t p = 0; p < kAxisOrders.size(); ++p) {
      std::array<int, 3> corner = {i, j, k};
      TetVertices tet;
      tet[0] = vertex_at(corner[0], corner[1], corner[2]);
      for (int s = 0; s < 3; ++s) {
        ++corner[kAxisOrders[p][s]];
        tet[s + 1] = vertex_at(corner[0], corner[1], corner[2]);
      }
      if (p >= 3) std::swap(tet[2], tet[3]);
      const absl::StatusOr<TetId> added = mesh.AddTet(tet);
      KERF_CHECK(added.ok());
    }
  }
  return mesh;
}

}  // namespace kerf::mesh
