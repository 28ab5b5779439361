#include "mesh/io/tet_mesh_data.h"

#include "absl/strings/str_cat.h"

namespace kerf::mesh {

absl::StatusOr<TetMesh> BuildTetMesh(const TetMeshData& data) {
  if (data.point_ids.size() != data.points.size()) {
    return absl::InvalidArgumentError(absl::StrCat("mesh data has ", data.points.size(),
                                                   " points but ", data.point_ids.size(), " ids"));
  }
  TetMesh mesh;
  for (const Eigen::Vector3d& p : data.points) mesh.AddVertex(p);
  for (std::size_t i = 0; i < data.tets.size(); ++i) {
    TetVertices tet;
    for (int c = 0; c < 4; ++c) {
      if (data.tets[i][c] >= data.points.size()) {
        return absl::InvalidArgumentError(absl::StrCat(
            "tet ", i, " names point index ", data.tets[i][c], " of ", data.points.size()));
      }
      tet[c] = static_cast<VertexId>(data.tets[i][c]);
    }
    if (absl::StatusOr<TetId> added = mesh.AddTet(tet); !added.ok()) return added.status();
  }
  return mesh;
}

TetMeshData ExtractTetMeshData(const TetMesh& mesh, bool current) {
  TetMeshData data;
  std::vector<std::uint32_t> dense(mesh.vertex_index_bound(), 0);
  data.points.reserve(mesh.vertex_count());
  data.point_ids.reserve(mesh.vertex_count());
  for (const VertexId v : mesh.vertices()) {
    dense[Index(v)] = static_cast<std::uint32_t>(data.points.size());
    data.points.push_back(current ? mesh.current_position(v) : mesh.rest_position(v));
    data.point_ids.push_back(Index(v));
  }
  data.tets.reserve(mesh.tet_count());
  for (const TetId t : mesh.tets()) {
    const TetVertices& v = mesh.tet(t);
    data.tets.push_back(
        {dense[Index(v[0])], dense[Index(v[1])], dense[Index(v[2])], dense[Index(v[3])]});
  }
  return data;
}

}  // namespace kerf::mesh
