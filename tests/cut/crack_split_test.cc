#include "cut/crack_split.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <set>

#include "cut/cone_apex.h"
#include "cut/one_tet.h"
#include "geometry/tet_measures.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {
namespace {

using mesh::VertexId;
using Triangle = std::array<VertexId, 3>;

Triangle Sorted(Triangle t) {
  std::sort(t.begin(), t.end());
  return t;
}

// The split tiles the tet: pieces of one sign of volume adding up to the tet's, every face of
// a piece either shared by exactly two pieces or on the tet's faces as the face rule splits
// them, and every crack face a face of the pieces.
void ExpectTiles(OneTet& tet, const TetCrack& crack, const CrackSplit& split) {
  double volume = 0;
  std::map<Triangle, int> faces;
  for (const mesh::TetVertices& t : split.tets) {
    const double v = std::abs(tet.Volume(t));
    EXPECT_GT(v, 1e-9) << "a flat piece";
    volume += v;
    for (const auto& f : mesh::kTetFaces) ++faces[Sorted({t[f[0]], t[f[1]], t[f[2]]})];
  }
  EXPECT_NEAR(volume, std::abs(tet.Volume(tet.corners())), 1e-12);
  std::map<Triangle, int> outside;
  for (const FaceSplit& f : crack.faces) {
    for (const Triangle& t : f.triangles) ++outside[Sorted(t)];
  }
  for (const auto& [face, count] : faces) {
    if (outside.contains(face)) {
      EXPECT_EQ(count, 1) << "a face triangle twice";
    } else {
      EXPECT_EQ(count, 2) << "an inner face not shared";
    }
  }
  for (const auto& [face, count] : outside) EXPECT_TRUE(faces.contains(face)) << "a hole";
  for (const Triangle& c : split.crack_faces) EXPECT_TRUE(faces.contains(Sorted(c)));
}

// Whether every piece reaches a triangle of the tet's faces off the crack through faces off the
// crack: none is walled in (cut free of the rest of the tet and of its neighbours), unless no
// triangle of the tet's faces is off the crack.
void ExpectNoPieceWalledIn(const TetCrack& crack, const CrackSplit& split) {
  std::set<Triangle> cracked, outside;
  for (const Triangle& c : split.crack_faces) cracked.insert(Sorted(c));
  for (const FaceSplit& f : crack.faces) {
    for (const Triangle& t : f.triangles) outside.insert(Sorted(t));
  }
  const std::size_t n = split.tets.size();
  std::vector<bool> reached(n, false);
  const auto faces_of = [&](std::size_t i) {
    std::vector<Triangle> faces;
    const mesh::TetVertices& t = split.tets[i];
    for (const auto& f : mesh::kTetFaces) faces.push_back(Sorted({t[f[0]], t[f[1]], t[f[2]]}));
    return faces;
  };
  for (std::size_t i = 0; i < n; ++i) {
    for (const Triangle& f : faces_of(i)) {
      if (outside.contains(f) && !cracked.contains(f)) reached[i] = true;
    }
  }
  // Where every triangle of the tet's faces lies on the crack, nothing can hold a piece.
  if (std::none_of(reached.begin(), reached.end(), [](bool r) { return r; })) return;
  for (bool grew = true; grew;) {
    grew = false;
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n && !reached[i]; ++j) {
        if (!reached[j]) continue;
        for (const Triangle& f : faces_of(i)) {
          const std::vector<Triangle> other = faces_of(j);
          if (!cracked.contains(f) && std::find(other.begin(), other.end(), f) != other.end()) {
            reached[i] = grew = true;
          }
        }
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) EXPECT_TRUE(reached[i]) << "piece " << i << " walled in";
}

TEST(CrackSplit, AnyPointsOnATetSplitIt) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(0, 1);
  int cones = 0, minimal = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    OneTet tet;
    for (const auto& [i, j] : mesh::kTetEdges) {
      if (unit(random) < 0.4) tet.CutEdge(i, j, 0.2 + 0.6 * unit(random));
    }
    for (int k = 0; k < 4; ++k) {
      if (unit(random) < 0.2) {
        Eigen::Vector3d w(0.2 + unit(random), 0.2 + unit(random), 0.2 + unit(random));
        tet.PointInFace(k, w / w.sum());
      }
      if (unit(random) < 0.15) tet.CornerOnCrack(k);
    }
    const TetCrack crack = tet.Crack();
    std::optional<CrackSplit> split = SplitWithoutApex(crack, tet.RestOf());
    if (!split) {
      split = SplitAsCone(crack, tet.Apex({0.3, 0.2, 0.25, 0.25}));
      ++cones;
    } else if (split->kind == CrackSplitKind::kMinimal) {
      ++minimal;
    }
    SCOPED_TRACE(::testing::Message() << "trial " << trial);
    ExpectTiles(tet, crack, *split);
    ReleaseWalledInPieces(crack, &*split);
    ExpectTiles(tet, crack, *split);
    ExpectNoPieceWalledIn(crack, *split);
    if (HasInnerCrack(crack)) {
      EXPECT_FALSE(split->crack_faces.empty());
    }
    if (HasFailure()) return;
  }
  EXPECT_GT(cones, 1000);
  EXPECT_GT(minimal, 100);
}

TEST(CrackSplit, ACornerCutOffIsCaseOne) {
  OneTet tet;
  tet.CutEdge(0, 1, 0.5);
  tet.CutEdge(0, 2, 0.4);
  tet.CutEdge(0, 3, 0.6);
  const TetCrack crack = tet.Crack();
  const std::optional<CrackSplit> split = SplitWithoutApex(crack, tet.RestOf());
  ASSERT_TRUE(split);
  EXPECT_EQ(split->cut_case, CutCase::kOneCornerOff);
  EXPECT_EQ(split->tets.size(), 4u);
  EXPECT_EQ(split->crack_faces.size(), 1u);
  ExpectTiles(tet, crack, *split);
}

TEST(CrackSplit, TwoAndTwoIsCaseTwo) {
  OneTet tet;
  tet.CutEdge(0, 2, 0.5);
  tet.CutEdge(0, 3, 0.5);
  tet.CutEdge(1, 2, 0.5);
  tet.CutEdge(1, 3, 0.5);
  const TetCrack crack = tet.Crack();
  const std::optional<CrackSplit> split = SplitWithoutApex(crack, tet.RestOf());
  ASSERT_TRUE(split);
  EXPECT_EQ(split->cut_case, CutCase::kTwoAndTwo);
  EXPECT_EQ(split->tets.size(), 6u);
  EXPECT_EQ(split->crack_faces.size(), 2u);
}

TEST(CrackSplit, ACrackThroughAnEdgeAndTwoCornersBisectsTheTet) {
  OneTet tet;
  tet.CutEdge(0, 1, 0.5);
  tet.CornerOnCrack(2);
  tet.CornerOnCrack(3);
  const TetCrack crack = tet.Crack();
  EXPECT_TRUE(HasInnerCrack(crack));
  const std::optional<CrackSplit> split = SplitWithoutApex(crack, tet.RestOf());
  ASSERT_TRUE(split);
  EXPECT_EQ(split->kind, CrackSplitKind::kBisected);
  EXPECT_EQ(split->tets.size(), 2u);
  EXPECT_EQ(split->crack_faces.size(), 1u);
}

TEST(CrackSplit, ACrackEndingInsideIsCaseThreeWithAFaceOfItsTwoPointsAndTheEdgePoint) {
  OneTet tet;
  tet.CutEdge(0, 1, 0.5);
  tet.PointInFace(3, {0.3, 0.3, 0.4});  // face 012
  tet.PointInFace(2, {0.3, 0.3, 0.4});  // face 013
  const TetCrack crack = tet.Crack();
  const std::optional<CrackSplit> split = SplitWithoutApex(crack, tet.RestOf());
  ASSERT_TRUE(split);
  EXPECT_EQ(split->cut_case, CutCase::kCrackOneEdge);
  EXPECT_EQ(split->crack_faces.size(), 1u);
  ExpectTiles(tet, crack, *split);
}

TEST(CrackSplit, NoPointsLeavesTheTetWholeAndAFaceOnTheCrackIsACrackFace) {
  OneTet tet;
  EXPECT_EQ(SplitWithoutApex(tet.Crack(), tet.RestOf())->tets.size(), 1u);
  tet.CornerOnCrack(1);
  tet.CornerOnCrack(2);
  tet.CornerOnCrack(3);
  const std::optional<CrackSplit> split = SplitWithoutApex(tet.Crack(), tet.RestOf());
  ASSERT_TRUE(split);
  EXPECT_EQ(split->kind, CrackSplitKind::kWhole);
  EXPECT_EQ(split->crack_faces.size(), 1u);
}

// A point in a face on the crack, nothing else (a crack face opened where the crack's front
// turns): a fan of three from the opposite corner, the face's three triangles on the crack.
TEST(CrackSplit, ALonePointInAFaceOnTheCrackIsAFanOfThree) {
  OneTet tet;
  for (const int i : {1, 2, 3}) tet.CornerOnCrack(i);
  tet.PointInFace(0, {1.0 / 3, 1.0 / 3, 1.0 / 3});  // face 123
  const TetCrack crack = tet.Crack();
  EXPECT_FALSE(HasInnerCrack(crack));
  const std::optional<CrackSplit> split = SplitWithoutApex(crack, tet.RestOf());
  ASSERT_TRUE(split);
  EXPECT_EQ(split->cut_case, CutCase::kFaceFan);
  EXPECT_EQ(split->tets.size(), 3u);
  EXPECT_EQ(split->crack_faces.size(), 3u);
  for (const mesh::TetVertices& t : split->tets) EXPECT_TRUE(mesh::TetHasVertex(t, VertexId(0)));
  ExpectTiles(tet, crack, *split);
}

// Case i with one of its cuts snapped to the far corner: corner 3 on the crack and edges 0-1 and
// 0-2 cut. The crack (3, e01, e02) cuts corner 0 off; a fan from corner 3 over face 012's three
// triangles is the split, no cone.
TEST(CrackSplit, ACutCornerSnappedOntoTheCrackIsAFanFromIt) {
  OneTet tet;
  tet.CornerOnCrack(3);
  tet.CutEdge(0, 1, 0.4);
  tet.CutEdge(0, 2, 0.4);
  const TetCrack crack = tet.Crack();
  ASSERT_TRUE(HasInnerCrack(crack));
  const std::optional<CrackSplit> split = SplitWithoutApex(crack, tet.RestOf());
  ASSERT_TRUE(split);
  EXPECT_EQ(split->cut_case, CutCase::kFaceFan);
  EXPECT_EQ(split->tets.size(), 3u);
  for (const mesh::TetVertices& t : split->tets) EXPECT_TRUE(mesh::TetHasVertex(t, VertexId(3)));
  ASSERT_EQ(split->crack_faces.size(), 1u);
  const Triangle& crack_face = split->crack_faces[0];
  EXPECT_NE(std::find(crack_face.begin(), crack_face.end(), VertexId(3)), crack_face.end());
  ExpectTiles(tet, crack, *split);
  ExpectNoPieceWalledIn(crack, *split);
}

// The tip's path through face 012 beside edge 0-1's cut, corners 2 and 3 on the crack: every
// point but corner 3 lies in face 012, so a fan from 3; the crack spans from 3 to the face's
// points on the crack: to the trace (point, e01) and to corner 2 through the point.
TEST(CrackSplit, AFansCrackReachesEveryPointOfItsFaceOnTheCrack) {
  OneTet tet;
  tet.CornerOnCrack(2);
  tet.CornerOnCrack(3);
  tet.CutEdge(0, 1, 0.4);
  tet.PointInFace(3, {0.3, 0.4, 0.3});
  const TetCrack crack = tet.Crack();
  ASSERT_TRUE(HasInnerCrack(crack));
  const std::optional<CrackSplit> split = SplitWithoutApex(crack, tet.RestOf());
  ASSERT_TRUE(split);
  EXPECT_EQ(split->cut_case, CutCase::kFaceFan);
  const VertexId inside = *crack.points[3].inside, e01 = *crack.points[3].on_edge[2];  // 1 to 0
  std::set<Triangle> faces;
  for (const Triangle& f : split->crack_faces) faces.insert(Sorted(f));
  EXPECT_TRUE(faces.contains(Sorted({VertexId(3), inside, e01})));
  EXPECT_TRUE(faces.contains(Sorted({VertexId(3), inside, VertexId(2)})));
  EXPECT_EQ(faces.size(), 2u);
  ExpectTiles(tet, crack, *split);
}

// A crack along edge 0-1 from corner 0 (on the crack) to its point: not the bisection's pattern
// (its crack runs through the opposite edge), yet every point lies in face 013 (and 012): the
// fan from the corner opposite is the bisection's two tets, no cone.
TEST(CrackSplit, ACrackAlongACutEdgeIsSplitInTwo) {
  OneTet tet;
  tet.CornerOnCrack(0);
  tet.CutEdge(0, 1, 0.5);
  const TetCrack crack = tet.Crack();
  const std::optional<CrackSplit> split = SplitWithoutApex(crack, tet.RestOf());
  ASSERT_TRUE(split);
  EXPECT_EQ(split->cut_case, CutCase::kFaceFan);
  EXPECT_EQ(split->tets.size(), 2u);
  EXPECT_TRUE(split->crack_faces.empty());
  ExpectTiles(tet, crack, *split);
}

// A crack whose trace lies in one face (the blade came in by it, its tip inside): a cone from a
// point the crack does not reach has no crack inside; from the blade's point, on the crack, its
// faces run from that point through the trace.
TEST(CrackSplit, AConeFromAPointOnTheCrackSpansATraceInOneFace) {
  OneTet tet;
  tet.PointInFace(3, {0.4, 0.3, 0.3});  // face 3: corners 0, 1, 2
  tet.CutEdge(0, 1, 0.5);
  const TetCrack crack = tet.Crack();
  ASSERT_FALSE(HasInnerCrack(crack));
  const mesh::VertexId apex = tet.Apex({0.3, 0.3, 0.2, 0.2});
  EXPECT_TRUE(SplitAsCone(crack, apex).crack_faces.empty());
  const CrackSplit split = SplitAsCone(crack, apex, /*apex_on_crack=*/true);
  ExpectTiles(tet, crack, split);
  ASSERT_EQ(split.crack_faces.size(), 1u);
  const std::vector<mesh::VertexId> trace = TracePoints(crack);
  for (const mesh::VertexId v : split.crack_faces[0]) {
    EXPECT_TRUE(v == apex || std::find(trace.begin(), trace.end(), v) != trace.end());
  }
}

// Three corners on the crack (their face lies on it) and the two edges from two of them to the
// fourth cut: the cone's faces through the on-crack face's edges would wall in the piece over
// it; none is.
TEST(CrackSplit, AConeWallsInNoPieceOverAFaceOnTheCrack) {
  OneTet tet;
  for (const int i : {1, 2, 3}) tet.CornerOnCrack(i);
  tet.CutEdge(0, 1, 0.3);
  tet.CutEdge(0, 2, 0.3);
  const TetCrack crack = tet.Crack();
  CrackSplit split = SplitAsCone(crack, tet.Apex({0.25, 0.25, 0.25, 0.25}));
  ReleaseWalledInPieces(crack, &split);
  ExpectTiles(tet, crack, split);
  ExpectNoPieceWalledIn(crack, split);
}

// A corner on the crack whose three edges are cut beside it (the blade passing near a vertex it
// snapped to): the corner cut off would be walled in by its three faces' triangles on the crack
// and the cut; let out, it stays with the rest of the tet.
TEST(CrackSplit, ACornerOnTheCrackCutOffIsNotWalledIn) {
  OneTet tet;
  tet.CornerOnCrack(0);
  for (const int j : {1, 2, 3}) tet.CutEdge(0, j, 0.4);
  const TetCrack crack = tet.Crack();
  std::optional<CrackSplit> split = SplitWithoutApex(crack, tet.RestOf());
  ASSERT_TRUE(split);
  EXPECT_EQ(split->cut_case, CutCase::kOneCornerOff);
  ReleaseWalledInPieces(crack, &*split);
  ExpectTiles(tet, crack, *split);
  ExpectNoPieceWalledIn(crack, *split);
}

// A crack face opened at its middle: the pieces still tile the tet, the face is three crack
// faces through the new point, and the point's pieces, joined through faces off the crack, are
// two sides (one on each side of the face), so parting the point opens the face.
TEST(CrackSplit, ACrackFaceOpenedAtItsMiddleHasTheCrackOnBothSidesOfItsPoint) {
  OneTet tet = CornerThreeCutOff();
  const TetCrack crack = tet.Crack();
  const auto rest = tet.RestOf();
  CrackSplit split = SplitAsCone(crack, tet.Apex(ConeApexWeights(crack, rest)));
  ASSERT_FALSE(split.crack_faces.empty());
  const Triangle face = split.crack_faces.front();
  Eigen::Vector4d middle = Eigen::Vector4d::Zero();
  for (const VertexId v : face) middle += tet.Weights(tet.Rest(v)) / 3;
  const VertexId point = tet.Apex(middle);
  const std::size_t tets = split.tets.size(), faces = split.crack_faces.size();

  ASSERT_TRUE(OpenCrackFace(&split, face, point));

  ExpectTiles(tet, crack, split);
  EXPECT_EQ(split.tets.size(), tets + 4);
  EXPECT_EQ(split.crack_faces.size(), faces + 2);
  EXPECT_EQ(std::count_if(split.crack_faces.begin(), split.crack_faces.end(),
                          [&](const Triangle& c) { return Sorted(c) == Sorted(face); }),
            0);
  std::set<Triangle> cracked;
  for (const Triangle& c : split.crack_faces) cracked.insert(Sorted(c));
  std::vector<std::size_t> star;
  for (std::size_t i = 0; i < split.tets.size(); ++i) {
    const mesh::TetVertices& t = split.tets[i];
    if (std::find(t.begin(), t.end(), point) != t.end()) star.push_back(i);
  }
  ASSERT_EQ(star.size(), 6u);
  // Sides: pieces of the star joined through a face at the point off the crack.
  std::vector<int> side(star.size(), -1);
  int sides = 0;
  for (std::size_t s = 0; s < star.size(); ++s) {
    if (side[s] >= 0) continue;
    side[s] = sides++;
    for (bool grew = true; grew;) {
      grew = false;
      for (std::size_t a = 0; a < star.size(); ++a) {
        for (std::size_t b = 0; b < star.size(); ++b) {
          if (side[a] != side[s] || side[b] >= 0) continue;
          std::vector<VertexId> shared;
          for (const VertexId v : split.tets[star[a]]) {
            const mesh::TetVertices& other = split.tets[star[b]];
            if (std::find(other.begin(), other.end(), v) != other.end()) shared.push_back(v);
          }
          if (shared.size() == 3 && !cracked.contains(Sorted({shared[0], shared[1], shared[2]}))) {
            side[b] = side[s], grew = true;
          }
        }
      }
    }
  }
  EXPECT_EQ(sides, 2);
}

// A crack face in one of the tet's faces (its three corners on the crack) opens in its one
// tet; the tet beside must open it alike. A face off the crack does not open.
TEST(CrackSplit, ACrackFaceInAFaceOfTheTetOpensItsOneTet) {
  OneTet tet;
  for (const int k : {0, 1, 2}) tet.CornerOnCrack(k);
  const TetCrack crack = tet.Crack();
  std::optional<CrackSplit> split = SplitWithoutApex(crack, tet.RestOf());
  ASSERT_TRUE(split);
  const mesh::TetVertices& c = tet.corners();
  const Triangle face = {c[0], c[1], c[2]};
  ASSERT_EQ(CrackFaceSides(*split, face), 1);
  EXPECT_EQ(CrackFaceSides(*split, {c[0], c[1], c[3]}), 0);  // off the crack
  const CrackSplit before = *split;
  const VertexId point = tet.Apex(Eigen::Vector4d(0.3, 0.3, 0.4, 0));
  EXPECT_FALSE(OpenCrackFace(&*split, {c[0], c[1], c[3]}, point));
  EXPECT_EQ(split->tets, before.tets);
  ASSERT_TRUE(OpenCrackFace(&*split, face, point));
  EXPECT_EQ(split->tets.size(), before.tets.size() + 2);
  double volume = 0;
  for (const mesh::TetVertices& t : split->tets) {
    EXPECT_GT(std::abs(tet.Volume(t)), 1e-9);
    volume += std::abs(tet.Volume(t));
  }
  EXPECT_NEAR(volume, std::abs(tet.Volume(c)), 1e-12);
  EXPECT_EQ(split->crack_faces.size(), 3u);
  for (const Triangle& f : split->crack_faces) {
    EXPECT_NE(std::find(f.begin(), f.end(), point), f.end());
  }
}

}  // namespace
}  // namespace kerf::cut
