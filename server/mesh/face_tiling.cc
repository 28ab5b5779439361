#include "mesh/face_tiling.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/str_cat.h"

namespace kerf::mesh {
namespace {

using Triangle = std::array<VertexId, 3>;

Triangle Sorted(Triangle t) {
  std::sort(t.begin(), t.end());
  return t;
}

double Area(const TetMesh& mesh, const Triangle& t) {
  const Eigen::Vector3d& a = mesh.rest_position(t[0]);
  return 0.5 * (mesh.rest_position(t[1]) - a).cross(mesh.rest_position(t[2]) - a).norm();
}

std::string Describe(const Triangle& t) {
  return absl::StrCat("(", Index(t[0]), ", ", Index(t[1]), ", ", Index(t[2]), ")");
}

}  // namespace

std::vector<Triangle> TrianglesOnFace(const TetMesh& mesh, const TetVertices& corners, int k,
                                      std::span<const TetVertices> pieces) {
  const auto& f = kTetFaces[k];
  const Eigen::Vector3d& origin = mesh.rest_position(corners[f[0]]);
  const Eigen::Vector3d normal = (mesh.rest_position(corners[f[1]]) - origin)
                                     .cross(mesh.rest_position(corners[f[2]]) - origin);
  const double tolerance = 1e-9 * std::abs(normal.dot(mesh.rest_position(corners[k]) - origin));
  std::vector<Triangle> triangles;
  for (const TetVertices& piece : pieces) {
    std::array<bool, 4> on;
    for (int m = 0; m < 4; ++m) {
      on[m] = std::abs(normal.dot(mesh.rest_position(piece[m]) - origin)) <= tolerance;
    }
    if (std::count(on.begin(), on.end(), true) != 3) continue;
    const int off = static_cast<int>(std::find(on.begin(), on.end(), false) - on.begin());
    triangles.push_back(Sorted({piece[(off + 1) % 4], piece[(off + 2) % 4], piece[(off + 3) % 4]}));
  }
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

absl::Status CheckOriginalFacesTiled(const TetMesh& uncut, const TetMesh& cut,
                                     const std::function<TetId(TetId)>& source_of,
                                     const std::function<VertexId(VertexId)>& same_as) {
  // The triangles of the cut mesh on each face (tet, local face) of the uncut one (its
  // vertices are the cut mesh's, at the same rest positions).
  absl::flat_hash_map<std::pair<std::uint32_t, int>, std::vector<Triangle>> tiles;
  for (const TetId piece : cut.tets()) {
    const TetId source = source_of(piece);
    for (int k = 0; k < 4; ++k) {
      for (const Triangle& t : TrianglesOnFace(cut, uncut.tet(source), k, {&cut.tet(piece), 1})) {
        tiles[{Index(source), k}].push_back(t);
      }
    }
  }
  // Each face tiled once, and an interior face alike from both sides.
  absl::flat_hash_map<std::array<std::uint32_t, 3>, std::pair<std::uint32_t, int>> first_side;
  for (const TetId t : uncut.tets()) {
    const TetVertices& corners = uncut.tet(t);
    for (int k = 0; k < 4; ++k) {
      const auto& f = kTetFaces[k];
      const Triangle face = Sorted({corners[f[0]], corners[f[1]], corners[f[2]]});
      std::vector<Triangle>& mine = tiles[{Index(t), k}];
      std::sort(mine.begin(), mine.end());  // gathered piece by piece
      double area = 0;
      for (const Triangle& tile : mine) area += Area(cut, tile);
      if (std::abs(area - Area(uncut, face)) > 1e-9 * Area(uncut, face)) {
        return absl::FailedPreconditionError(
            absl::StrCat("face ", Describe(face), " of tet ", Index(t), " is tiled ",
                         area / Area(uncut, face), " times by the tets cut from it"));
      }
      const auto [other, fresh] = first_side.try_emplace(
          std::array<std::uint32_t, 3>{Index(face[0]), Index(face[1]), Index(face[2])}, Index(t),
          k);
      if (fresh) continue;
      const auto canonical = [&](std::vector<Triangle> triangles) {
        if (!same_as) return triangles;
        for (Triangle& triangle : triangles) {
          for (VertexId& v : triangle) v = same_as(v);
          triangle = Sorted(triangle);
        }
        std::sort(triangles.begin(), triangles.end());
        return triangles;
      };
      if (canonical(tiles[other->second]) != canonical(mine)) {
        return absl::FailedPreconditionError(
            absl::StrCat("face ", Describe(face), " is split differently in the pieces of tets ",
                         other->second.first, " and ", Index(t)));
      }
    }
  }
  return absl::OkStatus();
}

}  // namespace kerf::mesh
