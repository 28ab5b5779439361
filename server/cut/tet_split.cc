#include "cut/tet_split.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <utility>

namespace kerf::cut {
namespace {

using mesh::Index;
using mesh::VertexId;

// The three tets of the prism with bottom triangle (A, B, C) and top (D, E, F) above it
// (A-D, B-E, C-F are its vertical edges), each quad split through its smallest-key vertex.
void SplitPrism(std::array<VertexId, 3> bottom, std::array<VertexId, 3> top,
                const std::vector<EdgeCut>& cuts, std::vector<mesh::TetVertices>* out) {
  auto key = [&](VertexId v) { return DiagonalKey(v, cuts); };
  // Relabel so that the smallest-key vertex is A.
  int smallest = 0;
  for (int i = 1; i < 6; ++i) {
    const VertexId candidate = i < 3 ? bottom[i] : top[i - 3];
    const VertexId current = smallest < 3 ? bottom[smallest] : top[smallest - 3];
    if (key(candidate) < key(current)) smallest = i;
  }
  if (smallest >= 3) {
    std::swap(bottom, top);
    smallest -= 3;
  }
  std::rotate(bottom.begin(), bottom.begin() + smallest, bottom.end());
  std::rotate(top.begin(), top.begin() + smallest, top.end());
  const auto [a, b, c] = bottom;
  const auto [d, e, f] = top;
  // Quads ABED and CADF are split through A (diagonals AE, AF): the tet ADEF comes off and
  // leaves the pyramid A-BCFE, whose base is split through its own smallest-key vertex.
  out->push_back({a, d, e, f});
  if (std::min(key(b), key(f)) < std::min(key(c), key(e))) {
    out->push_back({a, b, c, f});
    out->push_back({a, b, f, e});
  } else {
    out->push_back({a, b, c, e});
    out->push_back({a, c, f, e});
  }
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
  assert(cut != nullptr);
  return cut->corner_a == i ? cut->near_a : cut->near_b;
}

void Append(std::vector<mesh::TetVertices> tets, bool corner0_side, TetSplit* split) {
  for (const mesh::TetVertices& t : tets) {
    split->tets.push_back(t);
    split->on_corner0_side.push_back(corner0_side);
  }
}

}  // namespace

std::uint64_t DiagonalKey(VertexId v, const std::vector<EdgeCut>& cuts) {
  for (const EdgeCut& cut : cuts) {
    if (v == cut.near_a || v == cut.near_b) {
      return (std::uint64_t{1} << 32) + std::min(Index(cut.near_a), Index(cut.near_b));
    }
  }
  return Index(v);
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
    split.cut_case = CompleteCutCase::kOneCornerOff;
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
    split.cut_case = CompleteCutCase::kTwoAndTwo;
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

}  // namespace kerf::cut
