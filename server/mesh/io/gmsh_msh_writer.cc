#include "mesh/io/gmsh_msh_writer.h"

#include <charconv>

#include "absl/strings/str_cat.h"
#include "mesh/io/tet_mesh_data.h"

namespace kerf::mesh {
namespace {

void AppendExact(std::string* out, double value) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out->append(buffer, end);
}

}  // namespace

std::string FormatGmshMsh4(const TetMesh& mesh) {
  const TetMeshData data = ExtractTetMeshData(mesh);
  Eigen::Vector3d low = Eigen::Vector3d::Zero(), high = Eigen::Vector3d::Zero();
  if (!data.points.empty()) {
    low = high = data.points.front();
    for (const Eigen::Vector3d& p : data.points) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  }
  const std::size_t n = data.points.size();
  const std::int64_t min_tag = n ? data.point_ids.front() + 1 : 0;
  const std::int64_t max_tag = n ? data.point_ids.back() + 1 : 0;

  std::string out = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 0 1\n1";
  for (const double x : {low.x(), low.y(), low.z(), high.x(), high.y(), high.z()}) {
    out += ' ';
    AppendExact(&out, x);
  }
  absl::StrAppend(&out, " 0 0\n$EndEntities\n$Nodes\n1 ", n, " ", min_tag, " ", max_tag, "\n3 1 0 ",
                  n, "\n");
  for (const std::int64_t id : data.point_ids) absl::StrAppend(&out, id + 1, "\n");
  for (const Eigen::Vector3d& p : data.points) {
    AppendExact(&out, p.x());
    out += ' ';
    AppendExact(&out, p.y());
    out += ' ';
    AppendExact(&out, p.z());
    out += '\n';
  }
  const std::size_t t = data.tets.size();
  absl::StrAppend(&out, "$EndNodes\n$Elements\n1 ", t, " ", t ? 1 : 0, " ", t, "\n3 1 4 ", t, "\n");
  for (std::size_t i = 0; i < t; ++i) {
    absl::StrAppend(&out, i + 1);
    for (const std::uint32_t corner : data.tets[i]) {
      absl::StrAppend(&out, " ", data.point_ids[corner] + 1);
    }
    out += '\n';
  }
  out += "$EndElements\n";
  return out;
}

}  // namespace kerf::mesh
