#include "mesh/mesh_validation.h"

#include <algorithm>
#include <set>

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

absl::Status DefectsStatus(const std::vector<MeshDefect>& defects) {
  if (defects.empty()) return absl::OkStatus();
  constexpr std::size_t kShown = 5;
  std::string message = absl::StrCat("mesh has ", defects.size(), " defect(s): ");
  for (std::size_t i = 0; i < std::min(kShown, defects.size()); ++i) {
    absl::StrAppend(&message, i ? "; " : "", defects[i].message);
  }
  if (defects.size() > kShown) absl::StrAppend(&message, "; ...");
  return absl::FailedPreconditionError(message);
}

}  // namespace

std::vector<MeshDefect> FindMeshDefects(const TetMesh& mesh) {
  const std::vector<TetId> tets(mesh.tets().begin(), mesh.tets().end());
  const std::vector<VertexId> vertices(mesh.vertices().begin(), mesh.vertices().end());
  return FindMeshDefectsAmong(mesh, tets, vertices);
}

std::vector<MeshDefect> FindMeshDefectsAmong(const TetMesh& mesh, std::span<const TetId> tets,
                                             std::span<const VertexId> vertices) {
  std::vector<MeshDefect> defects;
  std::set<std::array<VertexId, 3>> over_shared;  // reported
  for (const TetId t : tets) {
    if (!mesh.IsAlive(t)) continue;
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
      if (sharing.size() <= 2) continue;
      std::vector<VertexId> corners = {a, b, c};
      std::sort(corners.begin(), corners.end());
      if (!over_shared.insert({corners[0], corners[1], corners[2]}).second) continue;
      std::vector<TetId> sharers(sharing.begin(), sharing.end());
      std::sort(sharers.begin(), sharers.end());
      std::string message = absl::StrCat("face (", VertexIdsText(corners), ") is shared by ",
                                         sharers.size(), " tets: ", TetIdsText(sharers));
      defects.push_back({MeshDefectKind::kOverSharedFace, std::move(sharers), std::move(corners), 0,
                         std::move(message)});
    }
  }
  for (const VertexId v : vertices) {
    if (mesh.IsAlive(v) && mesh.TetsAround(v).empty()) {
      defects.push_back({MeshDefectKind::kDanglingVertex,
                         {},
                         {v},
                         0,
                         absl::StrCat("vertex ", Index(v), " is used by no tet")});
    }
  }
  return defects;
}

absl::Status ValidateMesh(const TetMesh& mesh) { return DefectsStatus(FindMeshDefects(mesh)); }

absl::Status ValidateMeshAmong(const TetMesh& mesh, std::span<const TetId> tets,
                               std::span<const VertexId> vertices) {
  return DefectsStatus(FindMeshDefectsAmong(mesh, tets, vertices));
}

}  // namespace kerf::mesh
