// What the crack cutter (cut/crack_cutter.h) records of the crack and the blade: a point of the
// crack on an edge or inside a face, a tet the blade is in and its temporary pieces, the blade's
// points in a tet it meets, and a crack face's marks.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "cut/crack_split.h"
#include "cut/element_keys.h"
#include "cut/face_split.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut::crack_state {

inline constexpr mesh::VertexId kNoVertex{0xffffffffu};  // a point not made into a vertex yet
struct EdgePoint {
  double fraction;  // from the lower id
  mesh::VertexId vertex = kNoVertex;
};
struct FacePoint {
  Eigen::Vector3d barycentric;  // on the face key's vertices
  mesh::VertexId vertex = kNoVertex;
};
// Whether a tet's crack has traces, and the faces (origins) that hold all of them.
struct CrackTraces {
  bool any = false;
  std::vector<FaceKey> holding;
};
// A tet the blade is in (progressive), standing in the mesh as its temporary pieces.
struct OpenTet {
  mesh::TetVertices corners;  // origins
  mesh::TetId source;         // the tissue's tet it came from
  std::vector<mesh::TetId> pieces;
  std::vector<FaceKey> crack;  // the crack faces its pieces hold
  // Crack faces inside it opened at a point in their middle (CrackCutter::SplitUnits), by
  // origins.
  std::vector<FaceKey> openings;
  // The points its pieces were split at (temporary ones by their ids, which stay while the
  // blade moves them), whether a cone's apex is one of them, and whether a crack face in a face
  // of it was opened (alike in the unit beside: then the pieces are made again at each pose;
  // those inside it, `openings`, move with the points they lie between).
  std::array<FacePoints, 4> points;
  bool cone = false;
  bool opened_in_face = false;
  // The smallest rest volume of its pieces when they were laid out, or last found the same
  // by a split made anew (m^3; see CrackCutter::PiecesStand).
  double smallest_volume = 0;
  CrackTraces traces;  // of the crack at `points`
  // Its placed corners (CrackCutter::PlacedCorners), at the count of the tets' edits then.
  mutable std::optional<std::pair<std::uint64_t, mesh::TetVertices>> placed;
};
// The blade's points in a tet it meets now.
struct BladeIn {
  // Crossings of faces with no point for good, barycentric: temporary points.
  absl::flat_hash_map<FaceKey, Eigen::Vector3d, FaceKeyHash> faces;
  // Crossings of faces with a point for good, barycentric, at least kMinTemporaryWeight inside
  // the face: where they lie well inside a triangle of that point's fan, temporary points
  // beside it (FacePoints::beside), the crack running from the face's point to the blade.
  absl::flat_hash_map<FaceKey, Eigen::Vector3d, FaceKeyHash> beside;
  // Edges with no point for good that the blade passes through (lying in their plane, or its
  // tip on them), by the fraction from the lower id: temporary points.
  absl::flat_hash_map<EdgeKey, double> edges;
  // Edges with points that it passes through: it lies in the crack there, and meets every unit
  // at them.
  std::vector<EdgeKey> cut_edges;
  std::vector<FaceKey> crossed;  // every face the blade crosses
  Eigen::Vector4d apex;          // the crack's point inside: the tip, or the chord's middle
  bool tip_inside = false;
};
// A crack face: how many mark it, and the pose it was made at.
struct CrackFace {
  int marks = 0;
  std::size_t since = 0;
};
}  // namespace kerf::cut::crack_state
