#include "cut/crack_split.h"

#include <algorithm>

#include "base/check.h"
#include "cut/tet_split.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {
namespace {

using mesh::Index;
using mesh::TetVertices;
using mesh::VertexId;
using Triangle = std::array<VertexId, 3>;

Triangle Sorted(Triangle t) {
  std::sort(t.begin(), t.end(), [](VertexId a, VertexId b) { return Index(a) < Index(b); });
  return t;
}

bool Contains(const std::vector<VertexId>& set, VertexId v) {
  return std::find(set.begin(), set.end(), v) != set.end();
}

const std::vector<VertexId>& FaceVertices(const TetCrack& crack, int k) {
  return crack.face_vertices[k];
}

std::vector<std::array<VertexId, 2>> Traces(const TetCrack& crack) {
  std::vector<std::array<VertexId, 2>> traces;
  for (const FaceSplit& f : crack.faces) {
    for (const auto& s : f.trace) {
      if (std::find(traces.begin(), traces.end(), s) == traces.end()) traces.push_back(s);
    }
  }
  return traces;
}

// The point on the tet's edge between corners i and j, if it has one.
std::optional<VertexId> EdgePoint(const TetCrack& crack, int i, int j) {
  for (int k = 0; k < 4; ++k) {
    if (k == i || k == j) continue;
    const FacePoints& p = crack.points[k];
    for (int e = 0; e < 3; ++e) {
      const VertexId a = p.corners[e], b = p.corners[(e + 1) % 3];
      if ((a == crack.corners[i] && b == crack.corners[j]) ||
          (a == crack.corners[j] && b == crack.corners[i])) {
        return p.on_edge[e];
      }
    }
  }
  return std::nullopt;
}

// Whether the segment is an edge of a triangle of the tet's faces that lies on the crack and
// whose three edges are all trace segments: the cone's faces through them, with the triangle,
// would wall in the piece over it (cut it free), where the crack only runs in the face.
bool WallsInAPiece(const TetCrack& crack, const std::array<VertexId, 2>& segment,
                   const std::vector<std::array<VertexId, 2>>& traces) {
  const auto is_trace = [&](VertexId a, VertexId b) {
    const std::array<VertexId, 2> s = Index(a) < Index(b) ? std::array{a, b} : std::array{b, a};
    return std::find(traces.begin(), traces.end(), s) != traces.end();
  };
  for (const FaceSplit& f : crack.faces) {
    for (const Triangle& t : f.on_crack) {
      const bool has_segment = std::find(t.begin(), t.end(), segment[0]) != t.end() &&
                               std::find(t.begin(), t.end(), segment[1]) != t.end();
      if (has_segment && is_trace(t[0], t[1]) && is_trace(t[1], t[2]) && is_trace(t[2], t[0])) {
        return true;
      }
    }
  }
  return false;
}

void AddWholeFaceCracks(const TetCrack& crack, CrackSplit* split) {
  for (const FaceSplit& f : crack.faces) {
    split->crack_faces.insert(split->crack_faces.end(), f.on_crack.begin(), f.on_crack.end());
  }
}

// Whether the pieces' faces on each face of the tet are exactly that face's triangles.
bool TilesFacesAsTheRule(const TetCrack& crack, const std::vector<TetVertices>& tets) {
  for (int k = 0; k < 4; ++k) {
    const std::vector<VertexId> on_face = FaceVertices(crack, k);
    std::vector<Triangle> made, rule;
    for (const TetVertices& t : tets) {
      for (const auto& f : mesh::kTetFaces) {
        const Triangle face = {t[f[0]], t[f[1]], t[f[2]]};
        if (std::all_of(face.begin(), face.end(),
                        [&](VertexId v) { return Contains(on_face, v); })) {
          made.push_back(Sorted(face));
        }
      }
    }
    for (const Triangle& t : crack.faces[k].triangles) rule.push_back(Sorted(t));
    std::sort(made.begin(), made.end());
    std::sort(rule.begin(), rule.end());
    if (made != rule) return false;
  }
  return true;
}

// The pieces' faces that are inside the tet and have only trace points as vertices: the crack
// of a minimal case.
std::vector<Triangle> InnerFacesOf(const TetCrack& crack, const std::vector<TetVertices>& tets) {
  const std::vector<VertexId> points = TracePoints(crack);
  std::vector<Triangle> faces;
  for (const TetVertices& t : tets) {
    for (const auto& f : mesh::kTetFaces) {
      const Triangle face = Sorted({t[f[0]], t[f[1]], t[f[2]]});
      const bool on_trace =
          std::all_of(face.begin(), face.end(), [&](VertexId v) { return Contains(points, v); });
      bool on_tet_face = false;
      for (int k = 0; k < 4; ++k) {
        const std::vector<VertexId> on_face = FaceVertices(crack, k);
        on_tet_face = on_tet_face || std::all_of(face.begin(), face.end(),
                                                 [&](VertexId v) { return Contains(on_face, v); });
      }
      if (on_trace && !on_tet_face && std::find(faces.begin(), faces.end(), face) == faces.end()) {
        faces.push_back(face);
      }
    }
  }
  return faces;
}

}  // namespace

TetCrack MakeTetCrack(const TetVertices& corners, std::array<FacePoints, 4> points) {
  TetCrack crack{corners, {}, {}, {}};
  for (int k = 0; k < 4; ++k) {
    for (int j = 0; j < 3; ++j) points[k].corners[j] = corners[mesh::kTetFaces[k][j]];
    crack.faces[k] = SplitFace(points[k]);
    for (const Triangle& t : crack.faces[k].triangles) {
      for (const VertexId v : t) {
        if (!Contains(crack.face_vertices[k], v)) crack.face_vertices[k].push_back(v);
      }
    }
  }
  crack.points = points;
  return crack;
}

std::vector<VertexId> TracePoints(const TetCrack& crack) {
  std::vector<VertexId> points;
  for (const auto& s : Traces(crack)) {
    for (const VertexId v : s) {
      if (!Contains(points, v)) points.push_back(v);
    }
  }
  return points;
}

bool HasInnerCrack(const TetCrack& crack) {
  const std::vector<VertexId> points = TracePoints(crack);
  if (points.empty()) return false;
  for (int k = 0; k < 4; ++k) {
    const std::vector<VertexId> on_face = FaceVertices(crack, k);
    if (std::all_of(points.begin(), points.end(),
                    [&](VertexId v) { return Contains(on_face, v); })) {
      return false;
    }
  }
  return true;
}

std::optional<CrackSplit> SplitWithoutApex(const TetCrack& crack,
                                           const std::function<Eigen::Vector3d(VertexId)>& rest) {
  const bool inner = HasInnerCrack(crack);
  std::vector<EdgeCut> cuts;
  for (const auto& [i, j] : mesh::kTetEdges) {
    if (const std::optional<VertexId> e = EdgePoint(crack, i, j)) cuts.push_back({i, j, *e, *e});
  }
  std::vector<FacePoint> face_points;
  for (int k = 0; k < 4; ++k) {
    if (crack.points[k].inside) face_points.push_back({k, *crack.points[k].inside});
  }
  const std::vector<VertexId> trace_points = TracePoints(crack);
  const bool corner_traces = std::any_of(trace_points.begin(), trace_points.end(), [&](VertexId v) {
    return mesh::TetHasVertex(crack.corners, v);
  });
  CrackSplit split;
  if (cuts.empty() && face_points.empty()) {
    if (inner) return std::nullopt;  // a crack through corners only: a cone spans it
    split.tets.push_back(crack.corners);
    AddWholeFaceCracks(crack, &split);
    return split;
  }
  if (cuts.size() == 1 && face_points.empty()) {
    // Bisected at the edge point: the crack, if any, is the inner face through the opposite edge.
    const EdgeCut& cut = cuts[0];
    int c = -1, d = -1;
    for (int k = 0; k < 4; ++k) {
      if (k != cut.corner_a && k != cut.corner_b) (c < 0 ? c : d) = k;
    }
    const VertexId e = cut.near_a;
    const std::array<std::array<VertexId, 2>, 3> allowed = {
        {{std::min(e, crack.corners[c]), std::max(e, crack.corners[c])},
         {std::min(e, crack.corners[d]), std::max(e, crack.corners[d])},
         {std::min(crack.corners[c], crack.corners[d]),
          std::max(crack.corners[c], crack.corners[d])}}};
    const auto traces = Traces(crack);
    if (std::all_of(traces.begin(), traces.end(), [&](const auto& s) {
          return std::find(allowed.begin(), allowed.end(), s) != allowed.end();
        })) {
      split.kind = CrackSplitKind::kBisected;
      split.cut_case = CutCase::kSplitEdge;
      TetVertices near_a = crack.corners, near_b = crack.corners;
      near_a[cut.corner_b] = e;
      near_b[cut.corner_a] = e;
      split.tets = {near_a, near_b};
      if (inner) split.crack_faces.push_back({e, crack.corners[c], crack.corners[d]});
      AddWholeFaceCracks(crack, &split);
      return split;
    }
    return std::nullopt;
  }
  if (corner_traces || !inner) return std::nullopt;
  TetSplit minimal;
  if (face_points.empty()) {
    minimal = SplitCompletelyCutTet(crack.corners, cuts);
  } else if (face_points.size() == 2) {
    minimal = SplitCrackedTet(crack.corners, cuts, {face_points[0], face_points[1]}, rest);
  }
  if (minimal.cut_case == CutCase::kNone || !TilesFacesAsTheRule(crack, minimal.tets)) {
    return std::nullopt;
  }
  split.kind = CrackSplitKind::kMinimal;
  split.cut_case = minimal.cut_case;
  split.tets = std::move(minimal.tets);
  split.crack_faces = InnerFacesOf(crack, split.tets);
  AddWholeFaceCracks(crack, &split);
  return split;
}

Eigen::Vector4d PulledInside(const Eigen::Vector4d& w) {
  double pull = 0;
  for (int k = 0; k < 4; ++k) {
    if (w[k] < kApexMargin) pull = std::max(pull, (kApexMargin - w[k]) / (0.25 - w[k]));
  }
  return w + std::min(pull, 1.0) * (Eigen::Vector4d::Constant(0.25) - w);
}

CrackSplit SplitAsCone(const TetCrack& crack, VertexId apex) {
  CrackSplit split;
  split.kind = CrackSplitKind::kCone;
  split.cut_case = CutCase::kStar;
  for (const FaceSplit& f : crack.faces) {
    for (const Triangle& t : f.triangles) {
      KERF_CHECK(t[0] != apex && t[1] != apex && t[2] != apex);
      split.tets.push_back({apex, t[0], t[1], t[2]});
    }
  }
  if (HasInnerCrack(crack)) {
    const std::vector<std::array<VertexId, 2>> traces = Traces(crack);
    for (const auto& s : traces) {
      if (!WallsInAPiece(crack, s, traces)) split.crack_faces.push_back({apex, s[0], s[1]});
    }
  }
  AddWholeFaceCracks(crack, &split);
  return split;
}

}  // namespace kerf::cut
