#include "mesh/io/vtu_writer.h"

#include <cstring>

#include "absl/strings/str_cat.h"
#include "base/check.h"
#include "mesh/io/base64.h"
#include "mesh/io/tet_mesh_data.h"

namespace kerf::mesh {
namespace {

// Little-endian raw bytes of the values, after a UInt64 byte count, base64-encoded together.
template <typename T>
std::string EncodeBinary(const std::vector<T>& values) {
  static_assert(std::endian::native == std::endian::little, "VTU writer assumes little endian");
  const std::uint64_t byte_count = values.size() * sizeof(T);
  std::string raw(sizeof(byte_count) + byte_count, '\0');
  std::memcpy(raw.data(), &byte_count, sizeof(byte_count));
  if (byte_count > 0) std::memcpy(raw.data() + sizeof(byte_count), values.data(), byte_count);
  return internal::Base64Encode(raw);
}

template <typename T>
void AppendArray(std::string* out, absl::string_view name, int components,
                 const std::vector<T>& values) {
  constexpr absl::string_view type = std::is_same_v<T, double>         ? "Float64"
                                     : std::is_same_v<T, std::int64_t> ? "Int64"
                                                                       : "UInt8";
  absl::StrAppend(out, "        <DataArray type=\"", type, "\" Name=\"", name,
                  "\" NumberOfComponents=\"", components, "\" format=\"binary\">\n          ",
                  EncodeBinary(values), "\n        </DataArray>\n");
}

void AppendExtraArrays(std::string* out, const std::vector<VtuDataArray>& arrays,
                       std::size_t tuples) {
  for (const VtuDataArray& array : arrays) {
    std::visit(
        [&](const auto& values) {
          KERF_CHECK(values.size() == tuples * static_cast<std::size_t>(array.components));
          AppendArray(out, array.name, array.components, values);
        },
        array.values);
  }
}

}  // namespace

VtuDataArray RestPositionArray(const TetMesh& mesh) {
  std::vector<double> rest;
  rest.reserve(3 * mesh.vertex_count());
  for (const VertexId v : mesh.vertices()) {
    const Eigen::Vector3d& p = mesh.rest_position(v);
    rest.insert(rest.end(), {p.x(), p.y(), p.z()});
  }
  return {"rest_position", 3, std::move(rest)};
}

std::string FormatVtu(const TetMesh& mesh, const VtuExtraArrays& extra) {
  const TetMeshData data = ExtractTetMeshData(mesh, /*current=*/true);
  std::vector<double> coordinates;
  coordinates.reserve(3 * data.points.size());
  for (const Eigen::Vector3d& p : data.points)
    coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  std::vector<std::int64_t> connectivity, offsets;
  connectivity.reserve(4 * data.tets.size());
  offsets.reserve(data.tets.size());
  for (const auto& tet : data.tets) {
    connectivity.insert(connectivity.end(), tet.begin(), tet.end());
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  }
  const std::vector<std::uint8_t> types(data.tets.size(), 10);  // VTK_TETRA

  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
  absl::StrAppend(&out, "    <Piece NumberOfPoints=\"", data.points.size(), "\" NumberOfCells=\"",
                  data.tets.size(), "\">\n");
  absl::StrAppend(&out, "      <PointData>\n");
  AppendExtraArrays(&out, extra.point_data, data.points.size());
  absl::StrAppend(&out, "      </PointData>\n      <CellData>\n");
  AppendExtraArrays(&out, extra.cell_data, data.tets.size());
  absl::StrAppend(&out, "      </CellData>\n      <Points>\n");
  AppendArray(&out, "Points", 3, coordinates);
  absl::StrAppend(&out, "      </Points>\n      <Cells>\n");
  AppendArray(&out, "connectivity", 1, connectivity);
  AppendArray(&out, "offsets", 1, offsets);
  AppendArray(&out, "types", 1, types);
  absl::StrAppend(&out, "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
  return out;
}

}  // namespace kerf::mesh
