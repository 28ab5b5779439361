// The minimal subdivision of one tet cut all the way through (the paper's section 3.2,
// cases i and ii), as a pure function of vertex ids.
//
// A cut edge becomes two vertices at the same rest position, one on each side of the cut.
// The pieces on each side are a tet or a triangular prism; a prism is split into three tets
// by the rule "every quadrilateral face is split by the diagonal through its vertex with the
// smallest key" (Dompierre et al. 1999), which always gives a valid split. Keys are the
// vertex id for an original vertex and a key shared by the two vertices of a cut edge, so a
// neighbour that splits the same face, and the other side of the cut, choose the same
// diagonals: the result is conforming and keeps volume exactly.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "mesh/mesh_ids.h"

namespace kerf::cut {

// One cut edge of the tet being split: corners (local indices 0..3) and the new vertex on
// each corner's side. One vertex for both (near_a == near_b) is a closed cut: the crack's
// front passes through the edge there (progressive cutting, the blade on the edge now).
struct EdgeCut {
  int corner_a;
  int corner_b;
  mesh::VertexId near_a;  // the copy of the cut point that stays with corner a
  mesh::VertexId near_b;
  bool operator==(const EdgeCut&) const = default;
};

enum class CutCase {
  kNone,
  kOneCornerOff,     // case i: three cut edges around one corner; a tet and a prism (4 tets)
  kTwoAndTwo,        // case ii: four cut edges separating two corners from two; two prisms (6)
  kCrackOneEdge,     // case iii: one cut edge, the crack ending inside (6 tets)
  kCrackTwoEdges,    // case iv: two cut edges sharing a corner, the crack ending inside (8 tets)
  kCrackThreeEdges,  // case v: three cut edges in a path, the crack ending inside (9-10 tets)
  kStar,             // a cone from a point inside over the tet's faces (see SplitAsStar)
  kSplitEdge,        // snapped: one closed cut alone, two tets (SplitAtClosedCut)
  kFaceFan,          // every point but a corner's in its opposite face: a fan from the corner
};

// Where the blade's tip path crossed a face: one vertex, the base of the crack.
struct FacePoint {
  int face;  // the face opposite this local corner
  mesh::VertexId vertex;
  bool operator==(const FacePoint&) const = default;
};

struct TetSplit {
  CutCase cut_case = CutCase::kNone;
  // Replacement tets, in no particular orientation (the caller orients them on rest
  // positions), and for each the side it is on: true for the side of corner 0 (complete
  // cuts only).
  std::vector<mesh::TetVertices> tets;
  std::vector<bool> on_corner0_side;
};

// An empty result (kNone) when the cut edges are not those of case i or ii.
TetSplit SplitCompletelyCutTet(const mesh::TetVertices& corners, const std::vector<EdgeCut>& cuts);

// A tet whose crack ends inside it: the tip path crossed two faces and the swept surface cut
// the edges between them (cases iii, iv and v). The crack's edge points split as in a complete
// cut; the face points stay single. The choice of one inner diagonal (case iii) depends on
// geometry, so the rest positions are needed: `rest(v)` gives them. An empty result (kNone)
// for any other pattern, or when no valid split of this kind exists for the geometry.
TetSplit SplitCrackedTet(const mesh::TetVertices& corners, const std::vector<EdgeCut>& cuts,
                         const std::array<FacePoint, 2>& face_points,
                         const std::function<Eigen::Vector3d(mesh::VertexId)>& rest);

// A tet whose crack reaches a point `apex` strictly inside it (the blade's tip, while the
// blade is in the tet, or a point of a crack the minimal cases do not cover): the cone from the
// apex over the tet's faces, each face triangulated by the rule every splitter here follows,
// so a neighbour split by any of them conforms. A face with a face point fans from it, leaving
// a slit to each cut edge of the face; a face with two cut edges and no point is a corner
// triangle and a quadrilateral split by the key rule; a face with one closed cut is two
// triangles from its third corner; a face with two cuts pinned at one corner (a snapped
// crossing: the cut point is the corner) and its third edge cut is two triangles from that
// corner; a face with none is whole (triangles collapsed at pinned cuts get no tet). The crack
// then opens from the apex to the faces (its faces are the cone's faces through the slits).
// An empty result (kNone) when a face has another pattern or a tet would be flat or inverted.
TetSplit SplitAsStar(const mesh::TetVertices& corners, const std::vector<EdgeCut>& cuts,
                     const std::vector<FacePoint>& face_points, mesh::VertexId apex,
                     const std::function<Eigen::Vector3d(mesh::VertexId)>& rest);

// A tet whose only cut is closed (`cut.near_a == cut.near_b`: the crack's front crosses the
// edge, see Cutter): two tets, each with one corner of the edge replaced by the cut's vertex, so
// the faces at the edge are two triangles from their third corner, as SplitAsStar makes them.
TetSplit SplitAtClosedCut(const mesh::TetVertices& corners, const EdgeCut& cut);

// Leaves out the pieces with a repeated vertex: where a cut point is a corner itself (a
// snapped crossing, see Cutter), the pieces between them collapse, and the others tile the
// tet. Their faces on the tet's faces collapse alike in every neighbour.
void LeaveOutCollapsedTets(TetSplit* split);

}  // namespace kerf::cut
