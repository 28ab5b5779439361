// How one triangle face of the mesh is split by the points the crack has on it: the rule every
// tet at the face follows, so the two tets that share a face split it alike by construction.
//
// The triangulation depends only on the face's points: edge points (one at most inside each
// edge) and an inside point (the tip's crossing of the face, the blade's crossing of it now, or
// a hub the caller makes where three edges are cut and nothing is inside). Corners the crack
// passes through (snapped) never change it; they only add trace segments where the face has at
// most one point. The trace is where the crack crosses the face: the segments the crack surface
// of each tet at the face spans from.
//
//   inside point I:   a fan from I over the boundary; the trace runs from I to each edge point
//                     (and to each corner on the crack when no edge is cut); a point beside I
//                     (the blade crossing, elsewhere, a face whose point I is for good) splits
//                     the fan's triangle holding it in three, and the trace runs from I to it;
//   three edge points (no I): as above, I being the hub;
//   two edge points:  the corner between them cut off, the quadrilateral left split through its
//                     vertex of smallest key (corners before edge points, then by id: the rule of
//                     cut/tet_split.h); the trace is the segment between them;
//   one edge point E: two triangles from the opposite corner; the trace runs from E to each
//                     corner on the crack;
//   none:             the face whole; its edges between corners on the crack are trace.
// A triangle of the split whose three vertices are on the crack (its points, and its corners on
// the crack) lies on the crack: the blade swept in the face's plane there (a whole face when
// its three corners are on the crack), unless the caller keeps it off.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "mesh/mesh_ids.h"

namespace kerf::cut {

struct FacePoints {
  std::array<mesh::VertexId, 3> corners;
  // The point strictly inside edge k, from corners[k] to corners[(k + 1) % 3].
  std::array<std::optional<mesh::VertexId>, 3> on_edge;
  std::optional<mesh::VertexId> inside;  // strictly inside the face
  std::array<bool, 3> corner_on_crack = {false, false, false};
  // Triangles of the face's split that stay off the crack though their corners are on it (they
  // would wall a tet in: see CrackCutter), each with its vertices in any order.
  std::vector<std::array<mesh::VertexId, 3>> kept_off;
  // Whether edge k, from corners[k] to corners[(k + 1) % 3], lies on the crack where both its
  // corners do: false where they came onto the crack from parts of the blade's path farther apart
  // than the edge (the crack reaches each, not the edge between them).
  std::array<bool, 3> edge_on_crack = {true, true, true};
  // Only with `inside`: a second point strictly inside the triangle of inside's fan over the
  // boundary from `beside_between[0]` to `beside_between[1]` (either way round), through which
  // the crack runs from `inside` (the blade's crossing now of a face the tip's path crossed).
  std::optional<mesh::VertexId> beside = std::nullopt;
  std::array<mesh::VertexId, 2> beside_between{};

  friend bool operator==(const FacePoints&, const FacePoints&) = default;
};

// Whether the face needs a hub: three edge points and no inside point. The caller then puts one
// strictly inside the face (the middle of the edge points) as `inside`.
bool NeedsHub(const FacePoints& points);

struct FaceSplit {
  std::vector<std::array<mesh::VertexId, 3>> triangles;  // tile the face; each in face order
  std::vector<std::array<mesh::VertexId, 2>> trace;      // each with the smaller id first
  std::vector<std::array<mesh::VertexId, 3>> on_crack;   // the triangles on the crack
};

// The split of the face. Requires !NeedsHub(points).
FaceSplit SplitFace(const FacePoints& points);

// The face's points on the crack: its corners on the crack, its edge points and its inside point
// (not the point beside it: the blade, whose crack runs through the tet, not in the face).
std::vector<mesh::VertexId> PointsOnCrack(const FacePoints& points);

}  // namespace kerf::cut
