#include "cut/crack_split.h"

#include <algorithm>
#include <map>
#include <vector>

#include "absl/container/inlined_vector.h"
#include "base/check.h"
#include "cut/tet_split.h"
#include "geometry/tet_measures.h"
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

void AddWholeFaceCracks(const TetCrack& crack, CrackSplit* split) {
  for (const FaceSplit& f : crack.faces) {
    split->crack_faces.insert(split->crack_faces.end(), f.on_crack.begin(), f.on_crack.end());
  }
}

// Whether the pieces' faces on each face of the tet are exactly that face's triangles.
bool TilesFacesAsTheRule(const TetCrack& crack, const std::vector<TetVertices>& tets) {
  for (int k = 0; k < 4; ++k) {
    const std::vector<VertexId>& on_face = FaceVertices(crack, k);
    absl::InlinedVector<Triangle, 16> made, rule;
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
        const std::vector<VertexId>& on_face = FaceVertices(crack, k);
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

// The fan from a corner over the triangles of its opposite face, where every point of the tet
// but that corner lies in the face (the crack in that face, or spanning from the corner to it: a
// corner the crack passes through and cuts beside, case i with one cut snapped to its far end):
// the faces at the corner are split by their rule from it, so the fan tiles as the rule does.
// The crack of a fan from corner c with an inner crack (the corner is on it): from the corner to
// each edge inside face c's split joining two of the face's points on the crack.
std::vector<Triangle> FanCrackFaces(const TetCrack& crack, int c) {
  const std::vector<VertexId> on_crack = PointsOnCrack(crack.points[c]);
  // The crack runs along the edge from the corner to `v`, another corner, if the faces at that
  // edge say so (edge_on_crack); to a point the cut made, always.
  const auto edge_on_crack = [&](VertexId v) {
    for (const FacePoints& p : crack.points) {
      for (int j = 0; j < 3; ++j) {
        const VertexId a = p.corners[j], b = p.corners[(j + 1) % 3];
        if (((a == crack.corners[c] && b == v) || (b == crack.corners[c] && a == v)) &&
            !p.edge_on_crack[j]) {
          return false;
        }
      }
    }
    return true;
  };
  std::map<std::array<VertexId, 2>, int> edges;  // of face c's triangles, with how many hold each
  for (const Triangle& t : crack.faces[c].triangles) {
    for (int j = 0; j < 3; ++j) {
      const VertexId a = t[j], b = t[(j + 1) % 3];
      ++edges[Index(a) < Index(b) ? std::array<VertexId, 2>{a, b} : std::array<VertexId, 2>{b, a}];
    }
  }
  std::vector<Triangle> faces;
  for (const auto& [e, count] : edges) {
    if (count == 2 && Contains(on_crack, e[0]) && Contains(on_crack, e[1]) && edge_on_crack(e[0]) &&
        edge_on_crack(e[1])) {
      faces.push_back({crack.corners[c], e[0], e[1]});
    }
  }
  return faces;
}

std::optional<CrackSplit> SplitAsFan(const TetCrack& crack, bool inner) {
  for (int c = 0; c < 4; ++c) {
    const std::vector<VertexId>& face = FaceVertices(crack, c);
    bool all_in_face = true;
    for (int k = 0; k < 4 && all_in_face; ++k) {
      for (const VertexId v : FaceVertices(crack, k)) {
        if (v != crack.corners[c] && !Contains(face, v)) all_in_face = false;
      }
    }
    if (!all_in_face) continue;
    CrackSplit split;
    split.kind = CrackSplitKind::kMinimal;
    split.cut_case = CutCase::kFaceFan;
    for (const Triangle& t : crack.faces[c].triangles) {
      split.tets.push_back({crack.corners[c], t[0], t[1], t[2]});
    }
    if (!TilesFacesAsTheRule(crack, split.tets)) continue;
    if (inner) split.crack_faces = FanCrackFaces(crack, c);
    AddWholeFaceCracks(crack, &split);
    return split;
  }
  return std::nullopt;
}

}  // namespace

std::vector<std::array<VertexId, 2>> Traces(const TetCrack& crack) {
  std::vector<std::array<VertexId, 2>> traces;
  for (const FaceSplit& f : crack.faces) {
    for (const auto& s : f.trace) {
      if (std::find(traces.begin(), traces.end(), s) == traces.end()) traces.push_back(s);
    }
  }
  return traces;
}

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

std::vector<int> FacesHoldingTheTrace(const TetCrack& crack) {
  const std::vector<VertexId> points = TracePoints(crack);
  std::vector<int> faces;
  if (points.empty()) return faces;
  for (int k = 0; k < 4; ++k) {
    const std::vector<VertexId>& on_face = FaceVertices(crack, k);
    if (std::all_of(points.begin(), points.end(),
                    [&](VertexId v) { return Contains(on_face, v); })) {
      faces.push_back(k);
    }
  }
  return faces;
}

bool HasInnerCrack(const TetCrack& crack) {
  return !TracePoints(crack).empty() && FacesHoldingTheTrace(crack).empty();
}

std::optional<CrackSplit> SplitWithoutApex(const TetCrack& crack,
                                           const std::function<Eigen::Vector3d(VertexId)>& rest) {
  // A face with the blade's point beside its own fits none of the minimal cases.
  if (std::any_of(crack.points.begin(), crack.points.end(),
                  [](const FacePoints& p) { return p.beside.has_value(); })) {
    return std::nullopt;
  }
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
    // Else the crack runs along the cut edge or to a corner at it: a fan, if any, splits it.
  }
  if (std::optional<CrackSplit> fan = SplitAsFan(crack, inner)) return fan;
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

double SmallestAngle(const CrackSplit& split,
                     const std::function<Eigen::Vector3d(VertexId)>& rest) {
  double smallest = 180;
  for (const mesh::TetVertices& t : split.tets) {
    smallest = std::min(
        smallest, geometry::SmallestDihedralDeg(rest(t[0]), rest(t[1]), rest(t[2]), rest(t[3])));
  }
  return smallest;
}

int PiecesUnder(const CrackSplit& split, const std::function<Eigen::Vector3d(VertexId)>& rest,
                double degrees) {
  int under = 0;
  for (const mesh::TetVertices& t : split.tets) {
    if (geometry::SmallestDihedralDeg(rest(t[0]), rest(t[1]), rest(t[2]), rest(t[3])) < degrees)
      ++under;
  }
  return under;
}

CrackSplit SplitAsCone(const TetCrack& crack, VertexId apex, bool apex_on_crack) {
  CrackSplit split;
  split.kind = CrackSplitKind::kCone;
  split.cut_case = CutCase::kStar;
  for (const FaceSplit& f : crack.faces) {
    for (const Triangle& t : f.triangles) {
      KERF_CHECK(t[0] != apex && t[1] != apex && t[2] != apex);
      split.tets.push_back({apex, t[0], t[1], t[2]});
    }
  }
  if (apex_on_crack || HasInnerCrack(crack)) {
    for (const auto& s : Traces(crack)) split.crack_faces.push_back({apex, s[0], s[1]});
  }
  AddWholeFaceCracks(crack, &split);
  return split;
}

namespace {

bool HasAll(const TetVertices& t, const Triangle& face) {
  return std::all_of(face.begin(), face.end(),
                     [&](VertexId v) { return std::find(t.begin(), t.end(), v) != t.end(); });
}

}  // namespace

int CrackFaceSides(const CrackSplit& split, const Triangle& face) {
  const Triangle key = Sorted(face);
  if (std::none_of(split.crack_faces.begin(), split.crack_faces.end(),
                   [&](const Triangle& c) { return Sorted(c) == key; })) {
    return 0;
  }
  return static_cast<int>(std::count_if(split.tets.begin(), split.tets.end(),
                                        [&](const TetVertices& t) { return HasAll(t, face); }));
}

bool OpenCrackFace(CrackSplit* split, const Triangle& face, VertexId point) {
  if (CrackFaceSides(*split, face) == 0) return false;
  const Triangle key = Sorted(face);
  std::erase_if(split->crack_faces, [&](const Triangle& c) { return Sorted(c) == key; });
  std::vector<VertexId> off;  // the corners off the face of the tets with it
  std::erase_if(split->tets, [&](const TetVertices& t) {
    if (!HasAll(t, face)) return false;
    for (const VertexId v : t) {
      if (std::find(key.begin(), key.end(), v) == key.end()) off.push_back(v);
    }
    return true;
  });
  for (int e = 0; e < 3; ++e) {
    const VertexId a = key[e], b = key[(e + 1) % 3];
    split->crack_faces.push_back({point, a, b});
    for (const VertexId o : off) split->tets.push_back({point, a, b, o});
  }
  return true;
}

void ReleaseWalledInPieces(const TetCrack& crack, CrackSplit* split) {
  const auto on_a_face = [&](const Triangle& f) {
    for (int k = 0; k < 4; ++k) {
      const std::vector<VertexId>& on_face = FaceVertices(crack, k);
      if (Contains(on_face, f[0]) && Contains(on_face, f[1]) && Contains(on_face, f[2])) {
        return true;
      }
    }
    return false;
  };
  const std::size_t n = split->tets.size();
  for (bool released = true; released;) {
    std::vector<Triangle> cracked;
    for (const Triangle& c : split->crack_faces) cracked.push_back(Sorted(c));
    std::sort(cracked.begin(), cracked.end());
    const auto is_crack = [&](const Triangle& f) {
      return std::binary_search(cracked.begin(), cracked.end(), f);
    };
    std::vector<std::size_t> parent(n);
    for (std::size_t i = 0; i < n; ++i) parent[i] = i;
    const auto root = [&](std::size_t i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    std::vector<bool> anchored(n, false);
    std::map<Triangle, std::size_t> seen;
    for (std::size_t i = 0; i < n; ++i) {
      const TetVertices& t = split->tets[i];
      for (const auto& f : mesh::kTetFaces) {
        const Triangle face = Sorted({t[f[0]], t[f[1]], t[f[2]]});
        if (is_crack(face)) continue;
        if (on_a_face(face)) {
          anchored[i] = true;
        } else if (const auto [at, first] = seen.try_emplace(face, i); !first) {
          parent[root(i)] = root(at->second);
        }
      }
    }
    std::vector<bool> group_anchored(n, false);
    for (std::size_t i = 0; i < n; ++i) {
      if (anchored[i]) group_anchored[root(i)] = true;
    }
    // Each group walled in joins one group beside it: the crack faces between them go.
    std::map<Triangle, std::vector<std::size_t>> inner_crack;  // by face, its pieces
    for (std::size_t i = 0; i < n; ++i) {
      const TetVertices& t = split->tets[i];
      for (const auto& f : mesh::kTetFaces) {
        const Triangle face = Sorted({t[f[0]], t[f[1]], t[f[2]]});
        if (is_crack(face) && !on_a_face(face)) inner_crack[face].push_back(i);
      }
    }
    std::map<std::size_t, std::size_t> joins;  // walled group -> the group it joins
    for (const auto& [face, pieces] : inner_crack) {
      if (pieces.size() != 2) continue;
      const std::size_t a = root(pieces[0]), b = root(pieces[1]);
      if (a == b) continue;
      if (!group_anchored[a] && !joins.contains(a)) joins[a] = b;
      if (!group_anchored[b] && !joins.contains(b)) joins[b] = a;
    }
    std::vector<Triangle> walls;
    for (const auto& [face, pieces] : inner_crack) {
      if (pieces.size() != 2) continue;
      const std::size_t a = root(pieces[0]), b = root(pieces[1]);
      const auto joins_a = joins.find(a), joins_b = joins.find(b);
      if ((joins_a != joins.end() && joins_a->second == b) ||
          (joins_b != joins.end() && joins_b->second == a)) {
        walls.push_back(face);
      }
    }
    released = !walls.empty();
    std::erase_if(split->crack_faces, [&](const Triangle& c) {
      return std::find(walls.begin(), walls.end(), Sorted(c)) != walls.end();
    });
  }
}

}  // namespace kerf::cut
