#include "cut/tet_split.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <map>
#include <numeric>
#include <random>
#include <set>

#include "mesh/boundary_surface.h"
#include "mesh/connected_components.h"
#include "mesh/mesh_validation.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {
namespace {

using Eigen::Vector3d;
using mesh::TetMesh;
using mesh::VertexId;

// A mesh holding the original corners and, for each cut edge, two vertices at the cut point,
// created in a random order so that ids (and the diagonal rule) vary between trials.
struct CutTet {
  TetMesh mesh;
  mesh::TetVertices corners;
  std::vector<EdgeCut> cuts;
  double volume;
};

CutTet MakeCutTet(const std::array<Vector3d, 4>& x,
                  const std::vector<std::pair<int, int>>& cut_edges, std::mt19937& random) {
  std::uniform_real_distribution<double> fraction(0.1, 0.9);
  std::vector<std::pair<int, Vector3d>> points;  // (slot, position); slots 0..3 are corners
  for (int c = 0; c < 4; ++c) points.emplace_back(c, x[c]);
  for (std::size_t e = 0; e < cut_edges.size(); ++e) {
    const auto [i, j] = cut_edges[e];
    const Vector3d p = x[i] + fraction(random) * (x[j] - x[i]);
    points.emplace_back(4 + 2 * e, p);
    points.emplace_back(5 + 2 * e, p);
  }
  std::shuffle(points.begin(), points.end(), random);
  CutTet t;
  std::map<int, VertexId> id_of_slot;
  for (const auto& [slot, p] : points) id_of_slot[slot] = t.mesh.AddVertex(p);
  for (int c = 0; c < 4; ++c) t.corners[c] = id_of_slot[c];
  for (std::size_t e = 0; e < cut_edges.size(); ++e) {
    t.cuts.push_back(
        {cut_edges[e].first, cut_edges[e].second, id_of_slot[4 + 2 * e], id_of_slot[5 + 2 * e]});
  }
  t.volume = std::abs((x[1] - x[0]).cross(x[2] - x[0]).dot(x[3] - x[0])) / 6;
  return t;
}

// Adds the split's tets, each turned to positive orientation on rest positions.
void AddOriented(const TetSplit& split, TetMesh* mesh) {
  for (mesh::TetVertices t : split.tets) {
    const auto p = [&](int i) { return mesh->rest_position(t[i]); };
    if ((p(1) - p(0)).cross(p(2) - p(0)).dot(p(3) - p(0)) < 0) std::swap(t[2], t[3]);
    ASSERT_TRUE(mesh->AddTet(t).ok());
  }
}

// Checks the properties of ../shared/design/cutting.md that one split tet must keep.
void ExpectSplitKeepsTheProperties(CutTet& t, const TetSplit& split, std::size_t expected_tets,
                                   const std::array<Vector3d, 4>& x) {
  ASSERT_EQ(split.tets.size(), expected_tets);  // 7. minimal
  AddOriented(split, &t.mesh);
  double volume = 0;
  for (const mesh::TetId id : t.mesh.tets()) {
    const double v = RestVolume(t.mesh, id);
    EXPECT_GT(v, 0);  // 1. valid
    volume += v;
  }
  EXPECT_NEAR(volume, t.volume, 1e-12 * t.volume);     // 3. volume kept
  EXPECT_TRUE(mesh::FindMeshDefects(t.mesh).empty());  // 1, 2: valid and conforming
  const mesh::MeshComponents components = mesh::FindConnectedComponents(t.mesh);
  EXPECT_EQ(components.count, 2u);  // 5. separated
  for (std::size_t i = 0; i < split.tets.size(); ++i) {
    // Every tet on corner 0's side is in corner 0's component.
    const bool with_corner0 =
        components.tet_component[i] ==
        components.tet_component[std::distance(
            split.on_corner0_side.begin(),
            std::find(split.on_corner0_side.begin(), split.on_corner0_side.end(), true))];
    EXPECT_EQ(with_corner0, static_cast<bool>(split.on_corner0_side[i]));
  }
  // 6. each original face is tiled exactly once: the boundary triangles in its plane cover
  // its area exactly.
  for (const auto& face : mesh::kTetFaces) {
    const Vector3d &a = x[face[0]], &b = x[face[1]], &c = x[face[2]];
    const Vector3d normal = (b - a).cross(c - a);
    double covered = 0;
    for (const auto& tri : mesh::ExtractBoundarySurface(t.mesh)) {
      bool in_plane = true;
      for (const VertexId v : tri.vertices) {
        in_plane = in_plane && std::abs((t.mesh.rest_position(v) - a).dot(normal)) <
                                   1e-12 * normal.squaredNorm();
      }
      if (!in_plane) continue;
      const Vector3d &p = t.mesh.rest_position(tri.vertices[0]),
                     &q = t.mesh.rest_position(tri.vertices[1]),
                     &r = t.mesh.rest_position(tri.vertices[2]);
      covered += 0.5 * (q - p).cross(r - p).norm();
    }
    EXPECT_NEAR(covered, 0.5 * normal.norm(), 1e-12 * normal.norm());
  }
}

std::array<Vector3d, 4> RandomTet(std::mt19937& random) {
  std::uniform_real_distribution<double> coordinate(-1, 1);
  std::array<Vector3d, 4> x;
  do {
    for (Vector3d& p : x) p = Vector3d(coordinate(random), coordinate(random), coordinate(random));
  } while (std::abs((x[1] - x[0]).cross(x[2] - x[0]).dot(x[3] - x[0])) < 0.05);
  return x;
}

TEST(SplitCompletelyCutTet, CaseOneCornerOffInAllFourOrientations) {
  std::mt19937 random(1);
  for (int corner = 0; corner < 4; ++corner) {
    for (int trial = 0; trial < 50; ++trial) {
      const std::array<Vector3d, 4> x = RandomTet(random);
      std::vector<std::pair<int, int>> edges;
      for (int other = 0; other < 4; ++other) {
        if (other != corner) edges.emplace_back(corner, other);
      }
      std::shuffle(edges.begin(), edges.end(), random);
      CutTet t = MakeCutTet(x, edges, random);
      const TetSplit split = SplitCompletelyCutTet(t.corners, t.cuts);
      EXPECT_EQ(split.cut_case, CutCase::kOneCornerOff);
      ExpectSplitKeepsTheProperties(t, split, 4, x);
    }
  }
}

// Snapping: where a cut point is a corner (the blade through that corner), the pieces between
// them collapse and are left out; the rest tile the tet, on the two sides. Corner 0 cut off
// through corner 3 itself: a tet on corner 0's side and the pyramid over the face 1-2 side
// (two tets), three in all. Through corners 2 and 3: two tets. (Through all three: the whole
// tet, moved to the copies on corner 0's side: below.)
TEST(LeaveOutCollapsedTets, CutsThroughCornersLeaveTheTetTiledOnTwoSides) {
  std::mt19937 random(5);
  for (int through = 1; through <= 3; ++through) {
    for (int trial = 0; trial < 50; ++trial) {
      SCOPED_TRACE(::testing::Message() << "through " << through << " corners, trial " << trial);
      const std::array<Vector3d, 4> x = RandomTet(random);
      CutTet t = MakeCutTet(x, {{0, 1}, {0, 2}, {0, 3}}, random);
      // The last `through` cuts are at their far corner: that corner keeps its side, a copy of
      // it (one per corner, shared by every edge cut there) takes corner 0's.
      for (int k = 3 - through; k < 3; ++k) {
        EdgeCut& cut = t.cuts[k];
        ASSERT_TRUE(t.mesh.RemoveVertex(cut.near_a).ok());  // no cut point inside the edge
        ASSERT_TRUE(t.mesh.RemoveVertex(cut.near_b).ok());
        cut.near_a = t.mesh.AddVertex(x[cut.corner_b]);
        cut.near_b = t.corners[cut.corner_b];
      }
      TetSplit split = SplitCompletelyCutTet(t.corners, t.cuts);
      ASSERT_EQ(split.cut_case, CutCase::kOneCornerOff);
      LeaveOutCollapsedTets(&split);
      ASSERT_EQ(split.tets.size(), split.on_corner0_side.size());
      if (through < 3) {
        ExpectSplitKeepsTheProperties(t, split, through == 1 ? 3 : 2, x);
        continue;
      }
      ASSERT_EQ(split.tets.size(), 1u);
      EXPECT_TRUE(split.on_corner0_side[0]);
      mesh::TetVertices whole = split.tets[0], expected = {t.corners[0], t.cuts[0].near_a,
                                                           t.cuts[1].near_a, t.cuts[2].near_a};
      std::sort(whole.begin(), whole.end());
      std::sort(expected.begin(), expected.end());
      EXPECT_EQ(whole, expected);
    }
  }
}

TEST(SplitCompletelyCutTet, CaseTwoAndTwoInAllThreeOrientations) {
  std::mt19937 random(2);
  for (int partner = 1; partner < 4; ++partner) {
    for (int trial = 0; trial < 50; ++trial) {
      const std::array<Vector3d, 4> x = RandomTet(random);
      std::vector<int> far;
      for (int c = 1; c < 4; ++c) {
        if (c != partner) far.push_back(c);
      }
      std::vector<std::pair<int, int>> edges = {
          {0, far[0]}, {0, far[1]}, {partner, far[0]}, {far[1], partner}};
      std::shuffle(edges.begin(), edges.end(), random);
      CutTet t = MakeCutTet(x, edges, random);
      const TetSplit split = SplitCompletelyCutTet(t.corners, t.cuts);
      EXPECT_EQ(split.cut_case, CutCase::kTwoAndTwo);
      ExpectSplitKeepsTheProperties(t, split, 6, x);
    }
  }
}

TEST(SplitCompletelyCutTet, NeighboursSplitTheirSharedFaceTheSameWay) {
  // Two tets sharing face (0, 1, 2), both cut across it through edges 0-1 and 0-2 (a plane
  // separating corner 0): tet A = (0, 1, 2, 3) is case i; tet B = (0, 2, 1, 4) too. Their
  // shared face is split into a triangle and a quad, whose diagonal both must choose alike.
  std::mt19937 random(3);
  for (int trial = 0; trial < 100; ++trial) {
    const std::array<Vector3d, 5> x = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0),
                                       Vector3d(0.2, 0.2, 1), Vector3d(0.3, 0.3, -1)};
    std::uniform_real_distribution<double> fraction(0.1, 0.9);
    std::vector<int> slots(5 + 6);
    std::iota(slots.begin(), slots.end(), 0);
    std::shuffle(slots.begin(), slots.end(), random);
    // Slots 0..4 corners; 5..10 the two copies of the cuts on edges 0-1, 0-2, 0-3 / 0-4.
    const double f01 = fraction(random), f02 = fraction(random);
    std::map<int, Vector3d> position;
    for (int c = 0; c < 5; ++c) position[c] = x[c];
    position[5] = position[6] = x[0] + f01 * (x[1] - x[0]);
    position[7] = position[8] = x[0] + f02 * (x[2] - x[0]);
    position[9] = x[0] + fraction(random) * (x[3] - x[0]);
    position[10] = x[0] + fraction(random) * (x[4] - x[0]);
    TetMesh m;
    std::map<int, VertexId> id;
    for (const int slot : slots) id[slot] = m.AddVertex(position[slot]);
    // Edge 0-3 and edge 0-4 each need their own second copy.
    const VertexId near3 = m.AddVertex(position[9]), near4 = m.AddVertex(position[10]);
    const std::vector<EdgeCut> cuts_a = {
        {0, 1, id[5], id[6]}, {0, 2, id[7], id[8]}, {0, 3, id[9], near3}};
    const std::vector<EdgeCut> cuts_b = {
        {0, 2, id[5], id[6]}, {0, 1, id[7], id[8]}, {0, 3, id[10], near4}};
    ASSERT_EQ(SplitCompletelyCutTet({id[0], id[1], id[2], id[3]}, cuts_a).tets.size(), 4u);
    TetSplit a = SplitCompletelyCutTet({id[0], id[1], id[2], id[3]}, cuts_a);
    TetSplit b = SplitCompletelyCutTet({id[0], id[2], id[1], id[4]}, cuts_b);
    AddOriented(a, &m);
    AddOriented(b, &m);
    // Conforming: no defect, and no boundary triangle lies in the shared face's plane z = 0.
    EXPECT_TRUE(mesh::FindMeshDefects(m).empty());
    for (const auto& tri : mesh::ExtractBoundarySurface(m)) {
      bool in_plane = true;
      for (const VertexId v : tri.vertices) in_plane = in_plane && m.rest_position(v).z() == 0;
      EXPECT_FALSE(in_plane) << "the shared face was split two ways";
    }
    EXPECT_EQ(mesh::FindConnectedComponents(m).count, 2u);
  }
}

// Properties of a split whose crack ends inside the tet: valid, volume kept, one piece, each
// original face tiled once, and the crack open: no tet holds both copies of a cut point, and
// the crack's two sides are boundary of equal area.
void ExpectCrackedSplitKeepsTheProperties(CutTet& t, const TetSplit& split,
                                          std::size_t expected_tets,
                                          const std::array<Vector3d, 4>& x,
                                          const std::set<int>& one_side) {
  ASSERT_EQ(split.tets.size(), expected_tets);
  AddOriented(split, &t.mesh);
  double volume = 0;
  for (const mesh::TetId id : t.mesh.tets()) {
    const double v = RestVolume(t.mesh, id);
    EXPECT_GT(v, 0);
    volume += v;
    for (const EdgeCut& cut : t.cuts) {
      EXPECT_FALSE(mesh::TetHasVertex(t.mesh.tet(id), cut.near_a) &&
                   mesh::TetHasVertex(t.mesh.tet(id), cut.near_b));
    }
  }
  EXPECT_NEAR(volume, t.volume, 1e-12 * t.volume);
  EXPECT_TRUE(mesh::FindMeshDefects(t.mesh).empty());
  EXPECT_EQ(mesh::FindConnectedComponents(t.mesh).count, 1u);
  double on_faces = 0, crack_one_side = 0, crack_other_side = 0, surface = 0;
  for (const auto& face : mesh::kTetFaces) {
    surface += 0.5 * (x[face[1]] - x[face[0]]).cross(x[face[2]] - x[face[0]]).norm();
  }
  for (const auto& tri : mesh::ExtractBoundarySurface(t.mesh)) {
    const Vector3d &p = t.mesh.rest_position(tri.vertices[0]),
                   &q = t.mesh.rest_position(tri.vertices[1]),
                   &r = t.mesh.rest_position(tri.vertices[2]);
    const double area = 0.5 * (q - p).cross(r - p).norm();
    bool on_a_face = false;
    for (const auto& face : mesh::kTetFaces) {
      const Vector3d normal = (x[face[1]] - x[face[0]]).cross(x[face[2]] - x[face[0]]);
      bool in_plane = true;
      for (const Vector3d* point : {&p, &q, &r}) {
        in_plane =
            in_plane && std::abs((*point - x[face[0]]).dot(normal)) < 1e-12 * normal.squaredNorm();
      }
      on_a_face = on_a_face || in_plane;
    }
    if (on_a_face) {
      on_faces += area;
      continue;
    }
    // The crack's sides: the copies near the corners of `one_side`, and the others.
    bool on_one_side = false;
    for (const EdgeCut& cut : t.cuts) {
      const VertexId near = one_side.count(cut.corner_a) ? cut.near_a : cut.near_b;
      for (const VertexId v : tri.vertices) on_one_side = on_one_side || v == near;
    }
    (on_one_side ? crack_one_side : crack_other_side) += area;
  }
  EXPECT_NEAR(on_faces, surface, 1e-12 * surface);
  EXPECT_GT(crack_one_side, 1e-6 * surface);
  EXPECT_NEAR(crack_one_side, crack_other_side, 1e-12 * surface);
}

// The cut point of edge (i, j) if it is cut, else a new point on it (where a blade's plane
// would cross it).
Vector3d CutPointOrNew(const CutTet& t, const std::array<Vector3d, 4>& x, int i, int j,
                       std::mt19937& random) {
  for (const EdgeCut& cut : t.cuts) {
    if ((cut.corner_a == i && cut.corner_b == j) || (cut.corner_a == j && cut.corner_b == i)) {
      return t.mesh.rest_position(cut.near_a);
    }
  }
  std::uniform_real_distribution<double> fraction(0.2, 0.8);
  return x[i] + fraction(random) * (x[j] - x[i]);
}

// A point inside triangle (a, b, c), away from its edges.
Vector3d InsideTriangle(const Vector3d& a, const Vector3d& b, const Vector3d& c,
                        std::mt19937& random) {
  std::uniform_real_distribution<double> weight(0.15, 1.0);
  const double u = weight(random), v = weight(random), w = weight(random);
  return (u * a + v * b + w * c) / (u + v + w);
}

TEST(SplitCrackedTet, CaseOneEdgeInAllSixOrientations) {
  std::mt19937 random(5);
  for (const auto& [a, b] : mesh::kTetEdges) {
    for (int trial = 0; trial < 50; ++trial) {
      const std::array<Vector3d, 4> x = RandomTet(random);
      CutTet t = MakeCutTet(x, {{a, b}}, random);
      int c = -1, d = -1;
      for (int k = 0; k < 4; ++k) {
        if (k != a && k != b) (c < 0 ? c : d) = k;
      }
      const VertexId on_abc = t.mesh.AddVertex(InsideTriangle(x[a], x[b], x[c], random));
      const VertexId on_abd = t.mesh.AddVertex(InsideTriangle(x[a], x[b], x[d], random));
      const TetSplit split =
          SplitCrackedTet(t.corners, t.cuts, {FacePoint{d, on_abc}, FacePoint{c, on_abd}},
                          [&](VertexId v) { return t.mesh.rest_position(v); });
      EXPECT_EQ(split.cut_case, CutCase::kCrackOneEdge);
      ExpectCrackedSplitKeepsTheProperties(t, split, 6, x, {a});
    }
  }
}

TEST(SplitCrackedTet, CaseTwoEdgesInAllTwelveOrientations) {
  std::mt19937 random(6);
  std::uniform_real_distribution<double> fraction(0.2, 0.8);
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      for (int c = b + 1; c < 4; ++c) {
        if (b == a || c == a) continue;
        const int d = 6 - a - b - c;
        for (int trial = 0; trial < 30; ++trial) {
          const std::array<Vector3d, 4> x = RandomTet(random);
          std::vector<std::pair<int, int>> edges = {{a, b}, {c, a}};
          std::shuffle(edges.begin(), edges.end(), random);
          CutTet t = MakeCutTet(x, edges, random);
          // A blade plane cuts ab, ac and (beyond the crack's end) ad; the tip path runs near
          // that plane across faces abd and acd.
          const auto cut_point = [&](int i, int j) { return CutPointOrNew(t, x, i, j, random); };
          const Vector3d ab = cut_point(a, b), ac = cut_point(a, c), ad = cut_point(a, d);
          // Each face point is moved off the plane within its face, so that the crack is not
          // flat, as a swept (ruled) surface is not.
          const Vector3d on_abd_point = 0.7 * (ab + fraction(random) * (ad - ab)) +
                                        0.3 * InsideTriangle(x[a], x[b], x[d], random);
          const Vector3d on_acd_point = 0.7 * (ac + fraction(random) * (ad - ac)) +
                                        0.3 * InsideTriangle(x[a], x[c], x[d], random);
          const VertexId on_abd = t.mesh.AddVertex(on_abd_point);
          const VertexId on_acd = t.mesh.AddVertex(on_acd_point);
          const TetSplit split =
              SplitCrackedTet(t.corners, t.cuts, {FacePoint{c, on_abd}, FacePoint{b, on_acd}},
                              [&](VertexId v) { return t.mesh.rest_position(v); });
          EXPECT_EQ(split.cut_case, CutCase::kCrackTwoEdges);
          ExpectCrackedSplitKeepsTheProperties(t, split, 8, x, {a});
        }
      }
    }
  }
}

TEST(SplitCrackedTet, CaseThreeEdgesInAllTwelveOrientations) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> fraction(0.2, 0.8);
  std::array<int, 4> path = {0, 1, 2, 3};
  int orientations = 0;
  std::map<std::size_t, int> count_of_size;
  do {
    if (path[0] > path[3]) continue;  // a path and its reverse are one orientation
    ++orientations;
    const auto [a, b, c, d] = path;
    for (int trial = 0; trial < 30; ++trial) {
      const std::array<Vector3d, 4> x = RandomTet(random);
      std::vector<std::pair<int, int>> edges = {{a, b}, {c, b}, {c, d}};
      std::shuffle(edges.begin(), edges.end(), random);
      CutTet t = MakeCutTet(x, edges, random);
      // A blade plane separating {a, c} from {b, d} crosses ab, bc, cd and ad; the crack
      // stops before ad, its tip path running near the plane across faces abd and acd.
      const auto cut_point = [&](int i, int j) { return CutPointOrNew(t, x, i, j, random); };
      const Vector3d ab = cut_point(a, b), cd = cut_point(c, d), ad = cut_point(a, d);
      const VertexId on_abd = t.mesh.AddVertex(0.7 * (ab + fraction(random) * (ad - ab)) +
                                               0.3 * InsideTriangle(x[a], x[b], x[d], random));
      const VertexId on_acd = t.mesh.AddVertex(0.7 * (cd + fraction(random) * (ad - cd)) +
                                               0.3 * InsideTriangle(x[a], x[c], x[d], random));
      const TetSplit split =
          SplitCrackedTet(t.corners, t.cuts, {FacePoint{c, on_abd}, FacePoint{b, on_acd}},
                          [&](VertexId v) { return t.mesh.rest_position(v); });
      EXPECT_EQ(split.cut_case, CutCase::kCrackThreeEdges);
      // 9 tets when the diagonals that neighbours impose on faces abc and bcd allow a split
      // with no inner edge (a triangulation with all its vertices on the boundary has
      // 12 - 3 + inner edges tets); otherwise one inner edge, 10.
      ASSERT_TRUE(split.tets.size() == 9 || split.tets.size() == 10) << split.tets.size();
      ++count_of_size[split.tets.size()];
      ExpectCrackedSplitKeepsTheProperties(t, split, split.tets.size(), x, {a, c});
    }
  } while (std::next_permutation(path.begin(), path.end()));
  EXPECT_EQ(orientations, 12);
  std::printf("case v: %d splits of 9 tets, %d of 10\n", count_of_size[9], count_of_size[10]);
}

TEST(SplitCompletelyCutTet, IncompleteOrUnknownPatternsAreNotSplit) {
  const std::vector<EdgeCut> two = {{0, 1, VertexId{4}, VertexId{5}},
                                    {0, 2, VertexId{6}, VertexId{7}}};
  EXPECT_TRUE(SplitCompletelyCutTet({VertexId{0}, VertexId{1}, VertexId{2}, VertexId{3}}, two)
                  .tets.empty());
  // Three edges that are a path, not a star: not a complete cut.
  const std::vector<EdgeCut> path = {{0, 1, VertexId{4}, VertexId{5}},
                                     {1, 2, VertexId{6}, VertexId{7}},
                                     {2, 3, VertexId{8}, VertexId{9}}};
  EXPECT_TRUE(SplitCompletelyCutTet({VertexId{0}, VertexId{1}, VertexId{2}, VertexId{3}}, path)
                  .tets.empty());
}

// Closed cuts (one vertex for both sides: the crack's front on the edge) with nothing opening:
// the cone from the middle fills the tet, each face with a closed cut in two triangles from
// its third corner (two closed cuts: a corner triangle and a quadrilateral), so it meets the
// faces of the tets beside it. An open cut on a face with no point is still refused.
TEST(SplitAsStar, ClosedCutsAloneMakeAConeThatFillsTheTet) {
  const std::map<int, Vector3d> at = {{0, {0, 0, 0}},         {1, {1, 0, 0}},   {2, {0, 1, 0}},
                                      {3, {0, 0, 1}},         {4, {0.3, 0, 0}}, {5, {0, 0.6, 0}},
                                      {6, {0.25, 0.25, 0.25}}};
  const auto rest = [&](VertexId v) { return at.at(static_cast<int>(mesh::Index(v))); };
  const mesh::TetVertices corners = {VertexId{0}, VertexId{1}, VertexId{2}, VertexId{3}};
  const auto volume = [&](const mesh::TetVertices& t) {
    return (rest(t[1]) - rest(t[0])).cross(rest(t[2]) - rest(t[0])).dot(rest(t[3]) - rest(t[0])) /
           6;
  };
  const double whole = std::abs(volume(corners));
  const EdgeCut closed_01 = {0, 1, VertexId{4}, VertexId{4}};
  const EdgeCut closed_02 = {0, 2, VertexId{5}, VertexId{5}};
  for (const auto& [cuts, count] : std::vector<std::pair<std::vector<EdgeCut>, std::size_t>>{
           {{closed_01}, 6}, {{closed_01, closed_02}, 8}}) {
    const TetSplit split = SplitAsStar(corners, cuts, {}, VertexId{6}, rest);
    ASSERT_EQ(split.tets.size(), count);
    double total = 0;
    for (const mesh::TetVertices& t : split.tets) {
      EXPECT_GT(std::abs(volume(t)), 1e-3 * whole);
      total += std::abs(volume(t));
      EXPECT_FALSE(mesh::TetHasVertex(t, VertexId{0}) && mesh::TetHasVertex(t, VertexId{1}));
    }
    EXPECT_NEAR(total, whole, 1e-12);
  }
  const EdgeCut open_01 = {0, 1, VertexId{4}, VertexId{7}};
  EXPECT_TRUE(SplitAsStar(corners, {open_01}, {}, VertexId{6}, rest).tets.empty());
}

}  // namespace
}  // namespace kerf::cut
