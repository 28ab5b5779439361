// The split of one tet by the crack through it, for any points the crack has on its faces and
// edges: it cannot fail. Each face is split by the rule of cut/face_split.h, so the tets at a
// face always agree; inside, the tet is split by the paper's minimal cases where the pattern is
// one of them (bisection at a lone edge point, cases i-v of cut/tet_split.h, checked to make
// the same face triangles), and otherwise as a cone from one point inside (the apex) over the
// triangles of its faces, which tiles any tet whatever its faces carry.
//
// The crack inside the tet is spanned by the traces of its faces: where they do not all lie on
// one face, the crack's faces are the cone's faces from the apex through each trace segment (or
// the minimal case's crack). A triangle of a face on the crack is a crack face too. A split may
// wall pieces in (ReleaseWalledInPieces lets them out). Which
// vertices the crack parts is not decided here (cut/star_parting.h).
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "cut/face_split.h"
#include "cut/tet_split.h"
#include "mesh/mesh_ids.h"

namespace kerf::cut {

struct TetCrack {
  mesh::TetVertices corners;
  // Face k is opposite corner k, its corners in mesh::kTetFaces order; a face that NeedsHub has
  // its hub as `inside`.
  std::array<FacePoints, 4> points;
  std::array<FaceSplit, 4> faces;
  std::array<std::vector<mesh::VertexId>, 4> face_vertices;  // of each face's split
};

// The crack of a tet from its faces' points (their corners set from `corners`).
TetCrack MakeTetCrack(const mesh::TetVertices& corners, std::array<FacePoints, 4> points);

// The faces' trace segments, each once.
std::vector<std::array<mesh::VertexId, 2>> Traces(const TetCrack& crack);
// The distinct ends of the faces' trace segments, and whether they do not all lie on one face.
std::vector<mesh::VertexId> TracePoints(const TetCrack& crack);
bool HasInnerCrack(const TetCrack& crack);
// The faces (k: the face opposite corner k) that hold every trace point; none where there is no
// trace or it spans the tet (HasInnerCrack).
std::vector<int> FacesHoldingTheTrace(const TetCrack& crack);

enum class CrackSplitKind { kWhole, kBisected, kMinimal, kCone };

struct CrackSplit {
  CrackSplitKind kind = CrackSplitKind::kWhole;
  // kSplitEdge when bisected, the case when minimal, kStar for a cone, else kNone.
  CutCase cut_case = CutCase::kNone;
  std::vector<mesh::TetVertices> tets;  // tiling the tet, in no particular orientation
  std::vector<std::array<mesh::VertexId, 3>> crack_faces;  // each once
};

// The split without a new point: the tet whole, bisected or one of the minimal cases; nullopt
// when none fits (then SplitAsCone), as where a face has a point beside its inside one.
// `rest` gives rest positions (for case iii's choice).
std::optional<CrackSplit> SplitWithoutApex(
    const TetCrack& crack, const std::function<Eigen::Vector3d(mesh::VertexId)>& rest);

// The cone from `apex`, a vertex strictly inside the tet, over its faces' triangles. Its crack
// faces run from the apex through each trace segment where the traces do not all lie on one
// face, or wherever the apex is on the crack itself (`apex_on_crack`: the blade's point, where
// the crack reaches the blade from traces that may all lie in the face it came in by).
CrackSplit SplitAsCone(const TetCrack& crack, mesh::VertexId apex, bool apex_on_crack = false);

// Leaves out the inner crack faces that wall pieces in: a group of pieces joined through faces
// off the crack, none of whose triangles on the tet's faces is off the crack, would be cut free
// (the crack's traces there run in the tet's faces, or pass a corner on the crack and its edges'
// points at once). Each such group joins one group beside it: the crack faces between them go.
void ReleaseWalledInPieces(const TetCrack& crack, CrackSplit* split);

// How many of the split's tets have `face` (its vertices in any order) when it is a crack face:
// 2 inside the tet, 1 on one of its faces (a triangle of the face rule on the crack), 0 if it
// is no crack face of the split.
int CrackFaceSides(const CrackSplit& split, const std::array<mesh::VertexId, 3>& face);
// Opens the split's crack face `face` at `point`, a new vertex strictly inside it: each tet of
// the split with the face becomes three, from `point` over the face's edges, and the face three
// crack faces through `point`. A crack face none of whose vertices the crack parts (all lie on
// the crack's edge: the blade, the tip's path) stays shut; `point`, on the crack with one side
// of it on each side, is parted, so the crack opens there. A face on the tet's face must be
// opened alike by the tet beside it. False (and nothing changed) if `face` is no crack face.
bool OpenCrackFace(CrackSplit* split, const std::array<mesh::VertexId, 3>& face,
                   mesh::VertexId point);

// The smallest dihedral angle (degrees) of a split's tets, and how many of them have one under
// `degrees` (rest positions).
double SmallestAngle(const CrackSplit& split,
                     const std::function<Eigen::Vector3d(mesh::VertexId)>& rest);
int PiecesUnder(const CrackSplit& split, const std::function<Eigen::Vector3d(mesh::VertexId)>& rest,
                double degrees);

}  // namespace kerf::cut
