#include "mesh/mesh_validation.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"

namespace kerf::mesh {
namespace {

std::string TetIdsText(const std::vector<TetId>& tets) {
  return absl::StrJoin(tets, ", ",
                       [](std::string* out, TetId t) { absl::StrAppend(out, Index(t)); });
}

std::string VertexIdsText(const std::vector<VertexId>& vertices) {
  return absl::StrJoin(vertices, ", ",
                       [](std::string* out, VertexId v) { absl::StrAppend(out, Index(v)); });
}

bool HasRepeatedVertex(const TetVertices& v) {
  return v[0] == v[1] || v[0] == v[2] || v[0] == v[3] || v[1] == v[2] || v[1] == v[3] ||
         v[2] == v[3];
}

}  // namespace

std::vector<MeshDefect> FindMeshDefects(const TetMesh& mesh) {
  std::vector<MeshDefect> defects;
  for (const TetId t : mesh.tets()) {
    const TetVertices& v = mesh.tet(t);
    if (HasRepeatedVertex(v)) {
      defects.push_back({MeshDefectKind::kRepeatedVertex,
                         {t},
                         {v.begin(), v.end()},
                         0,
                         absl::StrCat("tet ", Index(t), " repeats a vertex: (",
                                      VertexIdsText({v.begin(), v.end()}), ")")});
      continue;  // its volume and faces say nothing more
    }
    const double volume = RestVolume(mesh, t);
    if (!(volume > 0)) {
      defects.push_back({MeshDefectKind::kNonPositiveVolume,
                         {t},
                         {v.begin(), v.end()},
                         volume,
                         absl::StrCat("tet ", Index(t), " has non-positive rest volume ", volume)});
    }
    for (const auto& face : kTetFaces) {
      const VertexId a = v[face[0]], b = v[face[1]], c = v[face[2]];
      const TetMesh::TetList sharing = mesh.TetsAroundFace(a, b, c);
      // Report each over-shared face once: from the lowest tet id sharing it.
      if (sharing.size() > 2 && *std::min_element(sharing.begin(), sharing.end()) == t) {
        std::vector<TetId> tets(sharing.begin(), sharing.end());
        std::sort(tets.begin(), tets.end());
        std::vector<VertexId> corners = {a, b, c};
        std::sort(corners.begin(), corners.end());
        std::string message = absl::StrCat("face (", VertexIdsText(corners), ") is shared by ",
                                           tets.size(), " tets: ", TetIdsText(tets));
        defects.push_back({MeshDefectKind::kOverSharedFace, std::move(tets), std::move(corners), 0,
                           std::move(message)});
      }
    }
  }
  for (const VertexId v : mesh.vertices()) {
    if (mesh.TetsAround(v).empty()) {
      defects.push_back({MeshDefectKind::kDanglingVertex,
                         {},
                         {v},
                         0,
                         absl::StrCat("vertex ", Index(v), " is used by no tet")});
    }
  }
  return defects;
}

absl::Status ValidateMesh(const TetMesh& mesh) {
  const std::vector<MeshDefect> defects = FindMeshDefects(mesh);
  if (defects.empty()) return absl::OkStatus();
  constexpr std::size_t kShown = 5;
  std::string message = absl::StrCat("mesh has ", defects.size(), " defect(s): ");
  for (std::size_t i = 0; i < std::min(kShown, defects.size()); ++i) {
    absl::StrAppend(&message, i ? "; " : "", defects[i].message);
  }
  if (defects.size() > kShown) absl::StrAppend(&message, "; ...");
  return absl::FailedPreconditionError(message);
}

}  // namespace kerf::mesh
