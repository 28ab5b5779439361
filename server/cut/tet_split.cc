#include "cut/tet_split.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "base/check.h"

namespace kerf::cut {
namespace {

using mesh::Index;
using mesh::VertexId;

// The key of a vertex for the diagonal rule: an original vertex's id; for the two copies of a
// cut point, the smaller of their ids, offset to sort after every original vertex, so both
// copies (and so both sides of the cut, and every neighbour) compare alike.
std::uint64_t DiagonalKey(VertexId v, const std::vector<EdgeCut>& cuts) {
  for (const EdgeCut& cut : cuts) {
    if (v == cut.near_a || v == cut.near_b) {
      return (std::uint64_t{1} << 32) + std::min(Index(cut.near_a), Index(cut.near_b));
    }
  }
  return Index(v);
}

// Which vertex of a quad (given in cyclic order) its splitting diagonal passes through.
using DiagonalChooser = std::function<VertexId(const std::array<VertexId, 4>&)>;

// The rule every face shared with a neighbour follows: through the smallest-key vertex.
DiagonalChooser KeyRule(const std::vector<EdgeCut>& cuts) {
  return [&cuts](const std::array<VertexId, 4>& q) {
    return *std::min_element(q.begin(), q.end(), [&](VertexId x, VertexId y) {
      return DiagonalKey(x, cuts) < DiagonalKey(y, cuts);
    });
  };
}

// True if the quad's chosen diagonal passes through v.
bool DiagonalTouches(const std::array<VertexId, 4>& q, VertexId v, const DiagonalChooser& choose) {
  const VertexId chosen = choose(q);
  const int at = static_cast<int>(std::find(q.begin(), q.end(), chosen) - q.begin());
  return v == q[at] || v == q[(at + 2) % 4];
}

// The three tets of the prism with bottom triangle (A, B, C) and top (D, E, F) above it
// (A-D, B-E, C-F are its vertical edges), its quads split as `choose` says. A prism can be
// split so unless its three diagonals turn the same way around it (the two cyclic choices):
// then some vertex carries two diagonals; it is A below, the tet ADEF comes off, and the
// pyramid A-BCFE is left. Returns false for a cyclic choice.
bool SplitPrism(std::array<VertexId, 3> bottom, std::array<VertexId, 3> top,
                const DiagonalChooser& choose, std::vector<mesh::TetVertices>* out) {
  for (int flip = 0; flip < 2; ++flip) {
    for (int turn = 0; turn < 3; ++turn) {
      const VertexId a = bottom[0], b = bottom[1], c = bottom[2];
      const VertexId d = top[0], e = top[1], f = top[2];
      if (DiagonalTouches({a, b, e, d}, a, choose) && DiagonalTouches({c, a, d, f}, a, choose)) {
        out->push_back({a, d, e, f});
        if (DiagonalTouches({b, c, f, e}, b, choose)) {
          out->push_back({a, b, c, f});
          out->push_back({a, b, f, e});
        } else {
          out->push_back({a, b, c, e});
          out->push_back({a, c, f, e});
        }
        return true;
      }
      std::rotate(bottom.begin(), bottom.begin() + 1, bottom.end());
      std::rotate(top.begin(), top.begin() + 1, top.end());
    }
    std::swap(bottom, top);
  }
  return false;
}

void SplitPrism(const std::array<VertexId, 3>& bottom, const std::array<VertexId, 3>& top,
                const std::vector<EdgeCut>& cuts, std::vector<mesh::TetVertices>* out) {
  const bool split = SplitPrism(bottom, top, KeyRule(cuts), out);
  KERF_CHECK(split);  // the key rule is never cyclic
}

// The two tets of the pyramid with this apex over the quad q (in cyclic order).
void SplitPyramid(VertexId apex, const std::array<VertexId, 4>& q, const DiagonalChooser& choose,
                  std::vector<mesh::TetVertices>* out) {
  const int at = static_cast<int>(std::find(q.begin(), q.end(), choose(q)) - q.begin());
  const VertexId p0 = q[at], p1 = q[(at + 1) % 4], p2 = q[(at + 2) % 4], p3 = q[(at + 3) % 4];
  out->push_back({apex, p0, p1, p2});
  out->push_back({apex, p0, p2, p3});
}

using Triangle = std::array<VertexId, 3>;

// The two triangles of a quad (in cyclic order) split as `choose` says.
std::array<Triangle, 2> QuadTriangles(const std::array<VertexId, 4>& q,
                                      const DiagonalChooser& choose) {
  const int at = static_cast<int>(std::find(q.begin(), q.end(), choose(q)) - q.begin());
  return {{{q[at], q[(at + 1) % 4], q[(at + 2) % 4]}, {q[at], q[(at + 2) % 4], q[(at + 3) % 4]}}};
}

// The tets joining `apex` to each boundary triangle of a region that does not contain it:
// a valid split exactly when the region is star-shaped from the apex. A triangle with a
// repeated vertex (collapsed at a cut point that is a corner: a snapped crossing) has no area
// and gets no tet.
std::vector<mesh::TetVertices> Cone(VertexId apex, const std::vector<Triangle>& boundary) {
  std::vector<mesh::TetVertices> tets;
  for (const Triangle& t : boundary) {
    const bool collapsed = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if (!collapsed && std::find(t.begin(), t.end(), apex) == t.end()) {
      tets.push_back({apex, t[0], t[1], t[2]});
    }
  }
  return tets;
}

double SignedVolume(const mesh::TetVertices& t,
                    const std::function<Eigen::Vector3d(VertexId)>& rest) {
  const Eigen::Vector3d a = rest(t[0]);
  return (rest(t[1]) - a).cross(rest(t[2]) - a).dot(rest(t[3]) - a) / 6;
}

// The four tets around the axis (p, q) of an octahedron whose other vertices form the cycle
// e0 e1 e2 e3, if they all have the same orientation (the axis lies inside), with the smallest
// absolute volume among them; else an empty list.
std::pair<std::vector<mesh::TetVertices>, double> OctahedronAround(
    VertexId p, VertexId q, const std::array<VertexId, 4>& e,
    const std::function<Eigen::Vector3d(VertexId)>& rest) {
  std::vector<mesh::TetVertices> tets;
  double smallest = std::numeric_limits<double>::infinity();
  int positive = 0;
  for (int i = 0; i < 4; ++i) {
    tets.push_back({p, q, e[i], e[(i + 1) % 4]});
    const double v = SignedVolume(tets.back(), rest);
    positive += v > 0;
    smallest = std::min(smallest, std::abs(v));
    if (v == 0) return {{}, 0};
  }
  if (positive != 0 && positive != 4) return {{}, 0};
  return {tets, smallest};
}

// The cut of edge (i, j) among `cuts`, or nullptr.
const EdgeCut* FindCut(const std::vector<EdgeCut>& cuts, int i, int j) {
  for (const EdgeCut& cut : cuts) {
    if ((cut.corner_a == i && cut.corner_b == j) || (cut.corner_a == j && cut.corner_b == i)) {
      return &cut;
    }
  }
  return nullptr;
}

// The copy of edge (i, j)'s cut point on corner i's side.
VertexId Near(const std::vector<EdgeCut>& cuts, int i, int j) {
  const EdgeCut* cut = FindCut(cuts, i, j);
  KERF_CHECK(cut != nullptr);
  return cut->corner_a == i ? cut->near_a : cut->near_b;
}

void Append(std::vector<mesh::TetVertices> tets, bool corner0_side, TetSplit* split) {
  for (const mesh::TetVertices& t : tets) {
    split->tets.push_back(t);
    split->on_corner0_side.push_back(corner0_side);
  }
}

}  // namespace

namespace {

// How many of the cut edges meet at each corner.
std::array<int, 4> CutsAtCorners(const std::vector<EdgeCut>& cuts) {
  std::array<int, 4> count{};
  for (const EdgeCut& cut : cuts) {
    ++count[cut.corner_a];
    ++count[cut.corner_b];
  }
  return count;
}

// The face point on the face opposite a corner, if the tip's path crossed it.
using FacePointOn = std::function<std::optional<VertexId>(int opposite)>;

// Case iii: one edge cut, the tip's path through the two faces at it.
TetSplit SplitCrackOneEdge(const mesh::TetVertices& corners, const std::vector<EdgeCut>& cuts,
                           const FacePointOn& face_point,
                           const std::function<Eigen::Vector3d(VertexId)>& rest) {
  TetSplit split;
  // Case iii: edge (a, b) cut; the tip path crossed faces abc and abd.
  const int a = cuts[0].corner_a, b = cuts[0].corner_b;
  int c = -1, d = -1;
  for (int k = 0; k < 4; ++k) {
    if (k != a && k != b) (c < 0 ? c : d) = k;
  }
  const std::optional<VertexId> f_c = face_point(d);  // on face abc
  const std::optional<VertexId> f_d = face_point(c);  // on face abd
  if (!f_c || !f_d) return split;
  split.tets.push_back({corners[a], cuts[0].near_a, *f_c, *f_d});
  split.tets.push_back({corners[b], cuts[0].near_b, *f_c, *f_d});
  // The rest is an octahedron with opposite pairs (a, b), (c, f_d), (d, f_c); split it
  // around whichever inner axis gives the better tets.
  auto [around_c, quality_c] =
      OctahedronAround(corners[c], *f_d, {corners[a], *f_c, corners[b], corners[d]}, rest);
  auto [around_d, quality_d] =
      OctahedronAround(corners[d], *f_c, {corners[a], *f_d, corners[b], corners[c]}, rest);
  const std::vector<mesh::TetVertices>& best = quality_c >= quality_d ? around_c : around_d;
  if (best.empty()) return TetSplit{};
  split.tets.insert(split.tets.end(), best.begin(), best.end());
  split.cut_case = CutCase::kCrackOneEdge;
  return split;
}

// Case iv: two edges at a corner cut, the tip's path through the two faces at the third.
TetSplit SplitCrackTwoEdges(const mesh::TetVertices& corners, const std::vector<EdgeCut>& cuts,
                            const FacePointOn& face_point,
                            const std::function<Eigen::Vector3d(VertexId)>& rest) {
  TetSplit split;
  // Case iv: edges (a, b) and (a, c) cut; the tip path crossed faces abd and acd.
  const std::array<int, 4> count = CutsAtCorners(cuts);
  const auto shared = std::find(count.begin(), count.end(), 2);
  if (shared == count.end()) return split;
  const int a = static_cast<int>(shared - count.begin());
  const int b = cuts[0].corner_a == a ? cuts[0].corner_b : cuts[0].corner_a;
  const int c = cuts[1].corner_a == a ? cuts[1].corner_b : cuts[1].corner_a;
  const int d = 6 - a - b - c;
  const std::optional<VertexId> f_b = face_point(c);  // on face abd
  const std::optional<VertexId> f_c = face_point(b);  // on face acd
  if (!f_b || !f_c) return split;
  const VertexId ab_a = Near(cuts, a, b), ab_b = Near(cuts, b, a);
  const VertexId ac_a = Near(cuts, a, c), ac_c = Near(cuts, c, a);
  // Corner a's side is the pyramid over the crack quad; the other side is the tet at edge
  // ad, a prism along bc and a pyramid at d. Only the quad on face abc is shared with a
  // neighbour (key rule); the crack quad and the quad between prism and pyramid are inside
  // this tet, so their diagonals are chosen for the best valid tets.
  const std::array<VertexId, 4> crack = {*f_b, ab_a, ac_a, *f_c};
  const std::array<VertexId, 4> inner = {corners[b], corners[c], *f_c, *f_b};
  const double volume = std::abs(SignedVolume(corners, rest));
  double best_quality = 0;
  for (int choice = 0; choice < 4; ++choice) {
    const VertexId crack_through = choice & 1 ? *f_b : ab_a;
    const VertexId inner_through = choice & 2 ? corners[b] : corners[c];
    const DiagonalChooser key_rule = KeyRule(cuts);
    const DiagonalChooser choose = [&](const std::array<VertexId, 4>& q) {
      // The crack quad appears with copies from either side; compare by cut point.
      const auto same_quad = [&](const std::array<VertexId, 4>& r) {
        return std::is_permutation(q.begin(), q.end(), r.begin());
      };
      const std::array<VertexId, 4> crack_far = {*f_b, ab_b, ac_c, *f_c};
      if (same_quad(crack)) return crack_through;
      if (same_quad(crack_far)) return crack_through == ab_a ? ab_b : crack_through;
      if (same_quad(inner)) return inner_through;
      return key_rule(q);
    };
    std::vector<mesh::TetVertices> tets;
    SplitPyramid(corners[a], crack, choose, &tets);
    tets.push_back({corners[a], corners[d], *f_b, *f_c});
    if (!SplitPrism({corners[b], ab_b, *f_b}, {corners[c], ac_c, *f_c}, choose, &tets)) continue;
    SplitPyramid(corners[d], inner, choose, &tets);
    double total = 0, smallest = std::numeric_limits<double>::infinity();
    for (const mesh::TetVertices& t : tets) {
      const double v = std::abs(SignedVolume(t, rest));
      total += v;
      smallest = std::min(smallest, v);
    }
    // Overlapping (inverted) tets make the absolute volumes add up to more than the tet.
    if (std::abs(total - volume) > 1e-10 * volume || !(smallest > best_quality)) continue;
    best_quality = smallest;
    split.tets = std::move(tets);
  }
  if (split.tets.empty()) return TetSplit{};
  split.cut_case = CutCase::kCrackTwoEdges;
  return split;
}

// Case v: three edges in a path cut, the tip's path through the two faces at its ends' edge.
TetSplit SplitCrackThreeEdges(const mesh::TetVertices& corners, const std::vector<EdgeCut>& cuts,
                              const FacePointOn& face_point,
                              const std::function<Eigen::Vector3d(VertexId)>& rest) {
  TetSplit split;
  // Case v: the cut edges are a path a-b-c-d; the tip path crossed faces abd and acd.
  const std::array<int, 4> count = CutsAtCorners(cuts);
  int a = -1, d = -1;
  for (int k = 0; k < 4; ++k) {
    if (count[k] == 1) (a < 0 ? a : d) = k;
    if (count[k] == 3 || count[k] == 0) return split;  // three edges around one corner
  }
  int b = -1;
  for (const EdgeCut& cut : cuts) {
    if (cut.corner_a == a) b = cut.corner_b;
    if (cut.corner_b == a) b = cut.corner_a;
  }
  const int c = 6 - a - b - d;
  if (b < 0 || FindCut(cuts, b, c) == nullptr || FindCut(cuts, c, d) == nullptr) return split;
  const std::optional<VertexId> f_p = face_point(c);  // on face abd
  const std::optional<VertexId> f_q = face_point(b);  // on face acd
  if (!f_p || !f_q) return split;
  const VertexId ab_a = Near(cuts, a, b), ab_b = Near(cuts, b, a);
  const VertexId bc_b = Near(cuts, b, c), bc_c = Near(cuts, c, b);
  const VertexId cd_c = Near(cuts, c, d), cd_d = Near(cuts, d, c);
  const VertexId va = corners[a], vb = corners[b], vc = corners[c], vd = corners[d];
  // The crack separates {a, c} from {b, d}; the two regions meet at the tet (a, d, fP, fQ)
  // along edge ad, where the crack ends. Each region is split as a cone from one of its
  // vertices, and the crack pentagon as a fan that both sides share.
  const DiagonalChooser key_rule = KeyRule(cuts);
  const std::array<Triangle, 2> on_abc = QuadTriangles({va, ab_a, bc_c, vc}, key_rule);
  const std::array<Triangle, 2> on_bcd = QuadTriangles({vb, bc_b, cd_d, vd}, key_rule);
  const std::array<VertexId, 5> crack_near_c = {*f_p, ab_a, bc_c, cd_c, *f_q};
  const std::array<VertexId, 5> crack_near_b = {*f_p, ab_b, bc_b, cd_d, *f_q};
  const double volume = std::abs(SignedVolume(corners, rest));
  double best_quality = 0;
  std::size_t best_count = std::numeric_limits<std::size_t>::max();
  for (int fan = 0; fan < 5; ++fan) {
    std::vector<Triangle> near_c = {on_abc[0],        on_abc[1],      {vc, bc_c, cd_c},
                                    {vc, cd_c, *f_q}, {va, vc, *f_q}, {va, ab_a, *f_p},
                                    {va, *f_p, *f_q}};
    std::vector<Triangle> near_b = {{vb, ab_b, bc_b}, on_bcd[0],        on_bcd[1],
                                    {cd_d, vd, *f_q}, {ab_b, vb, *f_p}, {vb, vd, *f_p},
                                    {vd, *f_p, *f_q}};
    for (int k = 1; k < 4; ++k) {
      near_c.push_back(
          {crack_near_c[fan], crack_near_c[(fan + k) % 5], crack_near_c[(fan + k + 1) % 5]});
      near_b.push_back(
          {crack_near_b[fan], crack_near_b[(fan + k) % 5], crack_near_b[(fan + k + 1) % 5]});
    }
    const std::array<VertexId, 7> apexes_c = {va, vc, ab_a, bc_c, cd_c, *f_p, *f_q};
    const std::array<VertexId, 7> apexes_b = {vb, vd, ab_b, bc_b, cd_d, *f_p, *f_q};
    std::array<std::vector<mesh::TetVertices>, 7> cones_c, cones_b;
    for (int i = 0; i < 7; ++i) {
      cones_c[i] = Cone(apexes_c[i], near_c);
      cones_b[i] = Cone(apexes_b[i], near_b);
    }
    const mesh::TetVertices between = {va, vd, *f_p, *f_q};
    for (const std::vector<mesh::TetVertices>& near : cones_c) {
      for (const std::vector<mesh::TetVertices>& far : cones_b) {
        const std::size_t pieces = near.size() + far.size() + 1;
        if (pieces > best_count) continue;
        double total = 0, smallest = std::numeric_limits<double>::infinity();
        const auto add = [&](const mesh::TetVertices& t) {
          const double v = std::abs(SignedVolume(t, rest));
          total += v;
          smallest = std::min(smallest, v);
        };
        for (const mesh::TetVertices& t : near) add(t);
        for (const mesh::TetVertices& t : far) add(t);
        add(between);
        if (std::abs(total - volume) > 1e-10 * volume || !(smallest > 1e-12 * volume)) continue;
        if (pieces == best_count && !(smallest > best_quality)) continue;
        best_count = pieces;
        best_quality = smallest;
        split.tets = near;
        split.tets.insert(split.tets.end(), far.begin(), far.end());
        split.tets.push_back(between);
      }
    }
  }
  if (split.tets.empty()) return TetSplit{};
  split.cut_case = CutCase::kCrackThreeEdges;
  return split;
}

}  // namespace

TetSplit SplitCrackedTet(const mesh::TetVertices& corners, const std::vector<EdgeCut>& cuts,
                         const std::array<FacePoint, 2>& face_points,
                         const std::function<Eigen::Vector3d(VertexId)>& rest) {
  const FacePointOn face_point = [&](int opposite) -> std::optional<VertexId> {
    for (const FacePoint& f : face_points) {
      if (f.face == opposite) return f.vertex;
    }
    return std::nullopt;
  };
  switch (cuts.size()) {
    case 1:
      return SplitCrackOneEdge(corners, cuts, face_point, rest);
    case 2:
      return SplitCrackTwoEdges(corners, cuts, face_point, rest);
    case 3:
      return SplitCrackThreeEdges(corners, cuts, face_point, rest);
    default:
      return TetSplit{};
  }
}

TetSplit SplitCompletelyCutTet(const mesh::TetVertices& corners, const std::vector<EdgeCut>& cuts) {
  TetSplit split;
  // Which corners each corner is cut from.
  std::array<int, 4> cut_count{};
  for (const EdgeCut& cut : cuts) {
    ++cut_count[cut.corner_a];
    ++cut_count[cut.corner_b];
  }
  if (cuts.size() == 3) {
    // Case i: the corner on all three cut edges comes off as a small tet.
    const auto lone = std::find(cut_count.begin(), cut_count.end(), 3);
    if (lone == cut_count.end()) return split;
    const int v = static_cast<int>(lone - cut_count.begin());
    const int x = (v + 1) % 4, y = (v + 2) % 4, z = (v + 3) % 4;
    split.cut_case = CutCase::kOneCornerOff;
    Append({{corners[v], Near(cuts, v, x), Near(cuts, v, y), Near(cuts, v, z)}}, v == 0, &split);
    std::vector<mesh::TetVertices> prism;
    SplitPrism({Near(cuts, x, v), Near(cuts, y, v), Near(cuts, z, v)},
               {corners[x], corners[y], corners[z]}, cuts, &prism);
    Append(prism, v != 0, &split);
    return split;
  }
  if (cuts.size() == 4 &&
      std::all_of(cut_count.begin(), cut_count.end(), [](int n) { return n == 2; })) {
    // Case ii: corners {0, p} stay together, the other two {q, r} form the far side; the
    // uncut edges are (0, p) and (q, r).
    int p = 1;
    while (FindCut(cuts, 0, p) != nullptr) ++p;
    int q = -1, r = -1;
    for (int i = 1; i < 4; ++i) {
      if (i == p) continue;
      (q < 0 ? q : r) = i;
    }
    if (FindCut(cuts, q, r) != nullptr) return split;
    split.cut_case = CutCase::kTwoAndTwo;
    std::vector<mesh::TetVertices> near_side, far_side;
    SplitPrism({corners[0], Near(cuts, 0, q), Near(cuts, 0, r)},
               {corners[p], Near(cuts, p, q), Near(cuts, p, r)}, cuts, &near_side);
    SplitPrism({corners[q], Near(cuts, q, 0), Near(cuts, q, p)},
               {corners[r], Near(cuts, r, 0), Near(cuts, r, p)}, cuts, &far_side);
    Append(near_side, true, &split);
    Append(far_side, false, &split);
  }
  return split;
}

TetSplit SplitAsStar(const mesh::TetVertices& corners, const std::vector<EdgeCut>& cuts,
                     const std::vector<FacePoint>& face_points, VertexId apex,
                     const std::function<Eigen::Vector3d(VertexId)>& rest) {
  const DiagonalChooser key_rule = KeyRule(cuts);
  std::vector<Triangle> boundary;
  for (int k = 0; k < 4; ++k) {
    const std::array<int, 3>& face = mesh::kTetFaces[k];
    std::optional<VertexId> point;
    for (const FacePoint& f : face_points) {
      if (f.face == k) point = f.vertex;
    }
    // The face's boundary, corner by corner, with both copies of each cut point between.
    std::vector<VertexId> ring;
    std::vector<const EdgeCut*> face_cuts;
    for (int n = 0; n < 3; ++n) {
      const int i = face[n], j = face[(n + 1) % 3];
      ring.push_back(corners[i]);
      if (const EdgeCut* cut = FindCut(cuts, i, j); cut != nullptr) {
        ring.push_back(Near(cuts, i, j));
        ring.push_back(Near(cuts, j, i));
        face_cuts.push_back(cut);
      }
    }
    if (point) {
      for (std::size_t n = 0; n < ring.size(); ++n) {
        const VertexId p = ring[n], q = ring[(n + 1) % ring.size()];
        const bool slit = std::any_of(face_cuts.begin(), face_cuts.end(), [&](const EdgeCut* c) {
          return (p == c->near_a && q == c->near_b) || (p == c->near_b && q == c->near_a);
        });
        if (!slit) boundary.push_back({*point, p, q});
      }
    } else if (face_cuts.empty()) {
      boundary.push_back({corners[face[0]], corners[face[1]], corners[face[2]]});
    } else if (face_cuts.size() == 2) {
      // The corner on both cut edges is cut off; the rest of the face is a quadrilateral.
      const EdgeCut& x = *face_cuts[0];
      const EdgeCut& y = *face_cuts[1];
      const int c =
          (x.corner_a == y.corner_a || x.corner_a == y.corner_b) ? x.corner_a : x.corner_b;
      const int cx = x.corner_a == c ? x.corner_b : x.corner_a;
      const int cy = y.corner_a == c ? y.corner_b : y.corner_a;
      boundary.push_back({corners[c], Near(cuts, c, cx), Near(cuts, c, cy)});
      for (const Triangle& t : QuadTriangles(
               {Near(cuts, cx, c), corners[cx], corners[cy], Near(cuts, cy, c)}, key_rule)) {
        boundary.push_back(t);
      }
    } else if (face_cuts.size() == 1 && face_cuts[0]->near_a == face_cuts[0]->near_b) {
      // A closed cut (the crack's front on the edge): two triangles from the third corner.
      const EdgeCut& x = *face_cuts[0];
      const int third = face[0] + face[1] + face[2] - x.corner_a - x.corner_b;
      boundary.push_back({corners[x.corner_a], x.near_a, corners[third]});
      boundary.push_back({x.near_a, corners[x.corner_b], corners[third]});
    } else if (face_cuts.size() == 3) {
      // Two cuts pinned at one corner (snapped: the crack passes through it) and the third
      // edge cut: the crack runs from the corner to that cut, two triangles.
      std::optional<int> pinned_at;
      for (const int c : face) {
        const auto pinned_here = [&](const EdgeCut* x) {
          return x->near_a == corners[c] && x->near_b == corners[c];
        };
        if (std::count_if(face_cuts.begin(), face_cuts.end(), pinned_here) == 2) pinned_at = c;
      }
      if (!pinned_at) return TetSplit{};
      const int c = *pinned_at;
      const int a = face[0] == c ? face[1] : face[0];
      const int b = face[0] + face[1] + face[2] - c - a;
      const EdgeCut* opposite = FindCut(cuts, a, b);
      if (opposite->near_a == opposite->near_b) return TetSplit{};
      boundary.push_back({corners[c], corners[a], Near(cuts, a, b)});
      boundary.push_back({corners[c], Near(cuts, b, a), corners[b]});
    } else {
      return TetSplit{};
    }
  }
  TetSplit split;
  split.tets = Cone(apex, boundary);
  const double volume = std::abs(SignedVolume(corners, rest));
  double total = 0;
  for (const mesh::TetVertices& t : split.tets) {
    const double v = std::abs(SignedVolume(t, rest));
    if (!(v > 1e-12 * volume)) return TetSplit{};
    total += v;
  }
  // Overlapping (inverted) tets make the absolute volumes add up to more than the tet.
  if (std::abs(total - volume) > 1e-10 * volume) return TetSplit{};
  split.cut_case = CutCase::kStar;
  return split;
}

TetSplit SplitAtClosedCut(const mesh::TetVertices& corners, const EdgeCut& cut) {
  KERF_CHECK(cut.near_a == cut.near_b);
  TetSplit split;
  split.cut_case = CutCase::kSplitEdge;
  for (const int replaced : {cut.corner_a, cut.corner_b}) {
    mesh::TetVertices piece = corners;
    piece[replaced] = cut.near_a;
    split.tets.push_back(piece);
  }
  return split;
}

void LeaveOutCollapsedTets(TetSplit* split) {
  std::size_t kept = 0;
  for (std::size_t k = 0; k < split->tets.size(); ++k) {
    mesh::TetVertices sorted = split->tets[k];
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) continue;
    split->tets[kept] = split->tets[k];
    if (!split->on_corner0_side.empty()) {
      split->on_corner0_side[kept] = split->on_corner0_side[k];
    }
    ++kept;
  }
  split->tets.resize(kept);
  if (!split->on_corner0_side.empty()) split->on_corner0_side.resize(kept);
}

}  // namespace kerf::cut
