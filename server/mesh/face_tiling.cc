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

FaceTiles TilesOfSource(const TetMesh& uncut, const TetMesh& cut, TetId source,
                        std::span<const TetId> pieces) {
  FaceTiles tiles;
  for (const TetId piece : pieces) {
    for (int k = 0; k < 4; ++k) {
      for (const Triangle& t : TrianglesOnFace(cut, uncut.tet(source), k, {&cut.tet(piece), 1})) {
        tiles[k].push_back(t);
      }
    }
  }
  for (std::vector<Triangle>& face : tiles) std::sort(face.begin(), face.end());
  return tiles;
}

absl::Status CheckFaceTiled(const TetMesh& uncut, const TetMesh& cut, TetId source, int k,
                            const std::vector<Triangle>& tiles,
                            const std::optional<OtherSide>& other,
                            const std::function<VertexId(VertexId)>& same_as) {
  const TetVertices& corners = uncut.tet(source);
  const auto& f = kTetFaces[k];
  const Triangle face = Sorted({corners[f[0]], corners[f[1]], corners[f[2]]});
  double area = 0;
  for (const Triangle& tile : tiles) area += Area(cut, tile);
  if (std::abs(area - Area(uncut, face)) > 1e-9 * Area(uncut, face)) {
    return absl::FailedPreconditionError(
        absl::StrCat("face ", Describe(face), " of tet ", Index(source), " is tiled ",
                     area / Area(uncut, face), " times by the tets cut from it"));
  }
  if (!other) return absl::OkStatus();
  const auto canonical = [&](std::vector<Triangle> triangles) {
    if (!same_as) return triangles;
    for (Triangle& triangle : triangles) {
      for (VertexId& v : triangle) v = same_as(v);
      triangle = Sorted(triangle);
    }
    std::sort(triangles.begin(), triangles.end());
    return triangles;
  };
  if (canonical(*other->tiles) != canonical(tiles)) {
    return absl::FailedPreconditionError(
        absl::StrCat("face ", Describe(face), " is split differently in the pieces of tets ",
                     Index(other->tet), " and ", Index(source)));
  }
  return absl::OkStatus();
}

absl::Status CheckOriginalFacesTiled(const TetMesh& uncut, const TetMesh& cut,
                                     const std::function<TetId(TetId)>& source_of,
                                     const std::function<VertexId(VertexId)>& same_as) {
  absl::flat_hash_map<std::uint32_t, std::vector<TetId>> pieces;
  for (const TetId piece : cut.tets()) pieces[Index(source_of(piece))].push_back(piece);
  absl::flat_hash_map<std::uint32_t, FaceTiles> tiles;
  for (const TetId t : uncut.tets())
    tiles[Index(t)] = TilesOfSource(uncut, cut, t, pieces[Index(t)]);
  // Each face tiled once, and an interior face alike from both sides.
  absl::flat_hash_map<std::array<std::uint32_t, 3>, std::pair<TetId, int>> first_side;
  for (const TetId t : uncut.tets()) {
    const TetVertices& corners = uncut.tet(t);
    for (int k = 0; k < 4; ++k) {
      const auto& f = kTetFaces[k];
      const Triangle face = Sorted({corners[f[0]], corners[f[1]], corners[f[2]]});
      const auto [other, fresh] = first_side.try_emplace(
          std::array<std::uint32_t, 3>{Index(face[0]), Index(face[1]), Index(face[2])}, t, k);
      std::optional<OtherSide> across;
      if (!fresh) {
        across = OtherSide{other->second.first,
                           &tiles.at(Index(other->second.first))[other->second.second]};
      }
      if (absl::Status s = CheckFaceTiled(uncut, cut, t, k, tiles.at(Index(t))[k], across, same_as);
          !s.ok()) {
        return s;
      }
    }
  }
  return absl::OkStatus();
}

}  // namespace kerf::mesh
