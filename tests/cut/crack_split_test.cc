#include "cut/crack_split.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <set>

#include "geometry/tet_measures.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {
namespace {

using mesh::VertexId;
using Triangle = std::array<VertexId, 3>;

// One tet and the points a crack may leave on it, with positions, for checking splits.
class OneTet {
 public:
  OneTet() {
    corners_ = {VertexId(0), VertexId(1), VertexId(2), VertexId(3)};
    at_ = {{0, {0, 0, 0}}, {1, {1, 0, 0}}, {2, {0.2, 1, 0}}, {3, {0.3, 0.3, 1}}};
  }
  Eigen::Vector3d Rest(VertexId v) const { return at_.at(static_cast<int>(v)); }
  std::function<Eigen::Vector3d(VertexId)> RestOf() const {
    return [this](VertexId v) { return Rest(v); };
  }

  // A point at `t` along the edge between corners i and j (shared by the faces at it).
  void CutEdge(int i, int j, double t) {
    const VertexId v = Add((1 - t) * Rest(corners_[i]) + t * Rest(corners_[j]));
    edge_points_[{std::min(i, j), std::max(i, j)}] = v;
  }
  // A point inside face k at the given weights on its corners (kTetFaces order).
  void PointInFace(int k, Eigen::Vector3d w) {
    const auto& f = mesh::kTetFaces[k];
    face_points_[k] = Add(w[0] * Rest(corners_[f[0]]) + w[1] * Rest(corners_[f[1]]) +
                          w[2] * Rest(corners_[f[2]]));
  }
  void CornerOnCrack(int i) { on_crack_[i] = true; }

  TetCrack Crack() {
    std::array<FacePoints, 4> points;
    for (int k = 0; k < 4; ++k) {
      const auto& f = mesh::kTetFaces[k];
      FacePoints& p = points[k];
      for (int j = 0; j < 3; ++j) {
        const int a = f[j], b = f[(j + 1) % 3];
        if (const auto it = edge_points_.find({std::min(a, b), std::max(a, b)});
            it != edge_points_.end()) {
          p.on_edge[j] = it->second;
        }
        p.corner_on_crack[j] = on_crack_[f[j]];
      }
      if (face_points_.contains(k)) p.inside = face_points_[k];
      p.corners = {corners_[f[0]], corners_[f[1]], corners_[f[2]]};
      if (NeedsHub(p)) {
        Eigen::Vector3d middle = Eigen::Vector3d::Zero();
        for (int j = 0; j < 3; ++j) middle += Rest(*p.on_edge[j]) / 3;
        p.inside = Add(middle);
      }
    }
    return MakeTetCrack(corners_, points);
  }
  VertexId Apex(const Eigen::Vector4d& w) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) x += w[k] * Rest(corners_[k]);
    return Add(x);
  }
  // The barycentric weights of `x` on the corners.
  Eigen::Vector4d Weights(const Eigen::Vector3d& x) const {
    Eigen::Matrix3d frame;
    for (int k = 0; k < 3; ++k) frame.col(k) = Rest(corners_[k + 1]) - Rest(corners_[0]);
    const Eigen::Vector3d w = frame.lu().solve(x - Rest(corners_[0]));
    return {1 - w.sum(), w.x(), w.y(), w.z()};
  }
  double Volume(const mesh::TetVertices& t) const {
    return geometry::SignedVolume(Rest(t[0]), Rest(t[1]), Rest(t[2]), Rest(t[3]));
  }
  const mesh::TetVertices& corners() const { return corners_; }

 private:
  VertexId Add(const Eigen::Vector3d& x) {
    const int id = 100 + static_cast<int>(at_.size());
    at_[id] = x;
    return VertexId(id);
  }
  mesh::TetVertices corners_;
  std::map<int, Eigen::Vector3d> at_;
  std::map<std::pair<int, int>, VertexId> edge_points_;
  std::map<int, VertexId> face_points_;
  std::array<bool, 4> on_crack_ = {false, false, false, false};
};

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

// The smallest dihedral angle of the cone from the apex at `weights` over the faces' triangles.
double SmallestConeAngle(OneTet& tet, const TetCrack& crack, const Eigen::Vector4d& weights) {
  const CrackSplit split = SplitAsCone(crack, tet.Apex(weights));
  double smallest = 180;
  for (const mesh::TetVertices& t : split.tets) {
    const auto angles =
        geometry::DihedralAnglesDeg(tet.Rest(t[0]), tet.Rest(t[1]), tet.Rest(t[2]), tet.Rest(t[3]));
    smallest = std::min(smallest, *std::min_element(angles.begin(), angles.end()));
  }
  return smallest;
}

// Two opposite edges cut, no crack inside: the tet is split only to match its faces, from an
// apex anywhere inside; the one chosen makes rounder pieces than the middle.
TEST(CrackSplit, AConeOnlyMatchingItsFacesHasItsRoundestApex) {
  OneTet tet;
  tet.CutEdge(0, 1, 0.3);
  tet.CutEdge(2, 3, 0.5);
  const TetCrack crack = tet.Crack();
  const auto rest = tet.RestOf();
  ASSERT_FALSE(HasInnerCrack(crack));
  ASSERT_FALSE(SplitWithoutApex(crack, rest));
  const Eigen::Vector4d chosen = ConeApexWeights(crack, rest);
  EXPECT_GE(chosen.minCoeff(), kApexMargin - 1e-12);
  EXPECT_GT(SmallestConeAngle(tet, crack, chosen),
            SmallestConeAngle(tet, crack, Eigen::Vector4d::Constant(0.25)) + 1);
}

// Corner 3 cut off by a tilted plane: a crack across the tet.
OneTet CornerThreeCutOff() {
  OneTet tet;
  tet.CutEdge(3, 0, 0.7);
  tet.CutEdge(3, 1, 0.5);
  tet.CutEdge(3, 2, 0.6);
  return tet;
}

// A crack across the tet (corner 3 cut off by a tilted plane): the apex stays on the crack's
// plane, inside by the margin, and its cone is no flatter than the one from the middle of the
// trace points.
TEST(CrackSplit, TheConesApexStaysOnTheCrack) {
  OneTet tet = CornerThreeCutOff();
  const TetCrack crack = tet.Crack();
  ASSERT_TRUE(HasInnerCrack(crack));
  const Eigen::Vector4d chosen = ConeApexWeights(crack, tet.RestOf());
  EXPECT_NEAR(chosen.sum(), 1, 1e-12);
  EXPECT_GE(chosen.minCoeff(), kApexMargin - 1e-12);
  const std::vector<VertexId> points = TracePoints(crack);
  ASSERT_EQ(points.size(), 3u);
  Eigen::Vector3d middle = Eigen::Vector3d::Zero();
  for (const VertexId v : points) middle += tet.Rest(v) / 3;
  const Eigen::Vector3d normal = (tet.Rest(points[1]) - tet.Rest(points[0]))
                                     .cross(tet.Rest(points[2]) - tet.Rest(points[0]))
                                     .normalized();
  EXPECT_NEAR(normal.dot(tet.Rest(tet.Apex(chosen)) - middle), 0, 1e-12);
  EXPECT_GE(SmallestConeAngle(tet, crack, chosen),
            SmallestConeAngle(tet, crack, PulledInside(tet.Weights(middle))));
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

// A corner cut whose third point lies near the corner: the minimal split (case i) has a sliver,
// and a cone over the same face triangles has none (what CrackCutter splits for good instead).
TEST(CrackSplit, ACornerCutNearTheCornerHasASliverThatAConeAvoids) {
  OneTet tet;
  tet.CutEdge(3, 0, 0.7);
  tet.CutEdge(3, 1, 0.7);
  tet.CutEdge(3, 2, 0.16);
  const TetCrack crack = tet.Crack();
  const std::optional<CrackSplit> minimal = SplitWithoutApex(crack, tet.RestOf());
  ASSERT_TRUE(minimal.has_value());
  EXPECT_EQ(minimal->kind, CrackSplitKind::kMinimal);
  EXPECT_LT(SmallestAngle(*minimal, tet.RestOf()), 5);
  const Eigen::Vector4d apex = ConeApexWeights(crack, tet.RestOf());
  const double cone = SmallestConeAngle(crack, tet.RestOf(), apex);
  EXPECT_GE(cone, 5);
  const CrackSplit split = SplitAsCone(crack, tet.Apex(apex));
  EXPECT_NEAR(SmallestAngle(split, tet.RestOf()), cone, 1e-9);
  const std::optional<Eigen::Vector4d> chosen =
      ConeApexWithFewerSlivers(crack, *minimal, tet.RestOf(), 5);
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(*chosen, apex);
  // Cut farther from the corner, the minimal split has no sliver and stays.
  OneTet round;
  round.CutEdge(3, 0, 0.5);
  round.CutEdge(3, 1, 0.5);
  round.CutEdge(3, 2, 0.5);
  const TetCrack round_crack = round.Crack();
  const std::optional<CrackSplit> round_split = SplitWithoutApex(round_crack, round.RestOf());
  ASSERT_TRUE(round_split.has_value());
  EXPECT_FALSE(ConeApexWithFewerSlivers(round_crack, *round_split, round.RestOf(), 5).has_value());
}

// A quad cut with three of its points near corner 0: the minimal split (case ii) has two pieces
// under 5 degrees. The best cone over the same face triangles still has one, yet fewer, so it is
// taken; with the fourth point farther along its edge the cone has as many, and the minimal
// split stays.
TEST(CrackSplit, AConeWithFewerSliversReplacesAMinimalSplit) {
  const auto quad = [](double last) {
    auto tet = std::make_unique<OneTet>();
    tet->CutEdge(0, 2, 0.06);
    tet->CutEdge(0, 3, 0.06);
    tet->CutEdge(1, 2, 0.06);
    tet->CutEdge(1, 3, last);
    return tet;
  };
  const std::unique_ptr<OneTet> fewer = quad(0.4);
  const TetCrack crack = fewer->Crack();
  const std::optional<CrackSplit> minimal = SplitWithoutApex(crack, fewer->RestOf());
  ASSERT_TRUE(minimal.has_value());
  EXPECT_EQ(minimal->kind, CrackSplitKind::kMinimal);
  EXPECT_EQ(PiecesUnder(*minimal, fewer->RestOf(), 5), 2);
  const std::optional<Eigen::Vector4d> apex =
      ConeApexWithFewerSlivers(crack, *minimal, fewer->RestOf(), 5);
  ASSERT_TRUE(apex.has_value());
  const CrackSplit cone = SplitAsCone(crack, fewer->Apex(*apex));
  EXPECT_EQ(PiecesUnder(cone, fewer->RestOf(), 5), 1);
  EXPECT_GT(SmallestAngle(cone, fewer->RestOf()), SmallestAngle(*minimal, fewer->RestOf()));

  const std::unique_ptr<OneTet> as_many = quad(0.5);
  const TetCrack other = as_many->Crack();
  const std::optional<CrackSplit> stays = SplitWithoutApex(other, as_many->RestOf());
  ASSERT_TRUE(stays.has_value());
  EXPECT_EQ(PiecesUnder(*stays, as_many->RestOf(), 5), 2);
  EXPECT_FALSE(ConeApexWithFewerSlivers(other, *stays, as_many->RestOf(), 5).has_value());
}

}  // namespace
}  // namespace kerf::cut
