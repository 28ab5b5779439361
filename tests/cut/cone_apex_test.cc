#include "cut/cone_apex.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "cut/one_tet.h"
#include "geometry/tet_measures.h"

namespace kerf::cut {
namespace {

using mesh::VertexId;
using Triangle = std::array<VertexId, 3>;

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
TEST(ConeApex, AConeOnlyMatchingItsFacesHasItsRoundestApex) {
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

// A crack across the tet (corner 3 cut off by a tilted plane): the apex stays on the crack's
// plane, inside by the margin, and its cone is no flatter than the one from the middle of the
// trace points.
TEST(ConeApex, TheConesApexStaysOnTheCrack) {
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

// A corner cut whose third point lies near the corner: the minimal split (case i) has a sliver,
// and a cone over the same face triangles has none (what CrackCutter splits for good instead).
TEST(ConeApex, ACornerCutNearTheCornerHasASliverThatAConeAvoids) {
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
TEST(ConeApex, AConeWithFewerSliversReplacesAMinimalSplit) {
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

// The distance of `x` from the plane through the trace points of `crack` (three of them).
double OffTracePlane(OneTet& tet, const TetCrack& crack, const Eigen::Vector3d& x) {
  const std::vector<VertexId> points = TracePoints(crack);
  EXPECT_EQ(points.size(), 3u);
  const Eigen::Vector3d normal = (tet.Rest(points[1]) - tet.Rest(points[0]))
                                     .cross(tet.Rest(points[2]) - tet.Rest(points[0]))
                                     .normalized();
  return std::abs(normal.dot(x - tet.Rest(points[0])));
}

// The apex is looked for near the blade's path too: one the path refuses is not taken where
// another candidate is near it; where none is, the apex is still inside by the margin.
TEST(ConeApex, AnApexAwayFromTheBladesPathIsNotTaken) {
  OneTet tet = CornerThreeCutOff();
  const TetCrack crack = tet.Crack();
  const auto rest = tet.RestOf();
  const Eigen::Vector4d free = ConeApexWeights(crack, rest);
  const ApexNearPath away_from_free = [&](const Eigen::Vector4d& w) {
    return (w - free).norm() > 0.05;
  };
  const Eigen::Vector4d chosen = ConeApexWeights(crack, rest, away_from_free);
  EXPECT_TRUE(away_from_free(chosen));
  EXPECT_GE(chosen.minCoeff(), kApexMargin - 1e-12);
  const auto corner = [&](int k) { return tet.Rest(tet.corners()[k]); };
  EXPECT_LE(OffTracePlane(tet, crack, tet.Rest(tet.Apex(chosen))),
            kApexReach * geometry::MeanEdgeLength(corner(0), corner(1), corner(2), corner(3)));
  const Eigen::Vector4d refused =
      ConeApexWeights(crack, rest, [](const Eigen::Vector4d&) { return false; });
  EXPECT_GE(refused.minCoeff(), kApexMargin - 1e-12);
}

// Where the swept surface bends, an apex near it may still have a crack face that leaves it: of
// the candidates near the path, one whose cone's crack faces have their middles near it too is
// taken before a rounder one. Here the path is everywhere but a small ball around the middle of a
// crack face of the cone the search takes without a path.
TEST(ConeApex, TheConesFacesStayNearWhereThePathBends) {
  OneTet tet = CornerThreeCutOff();
  const TetCrack crack = tet.Crack();
  const auto rest = tet.RestOf();
  const auto at = [&](const Eigen::Vector4d& w) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) x += w[k] * tet.Rest(tet.corners()[k]);
    return x;
  };
  const auto middle_of = [&](const Eigen::Vector4d& apex, const std::array<VertexId, 2>& s) {
    return Eigen::Vector3d((at(apex) + tet.Rest(s[0]) + tet.Rest(s[1])) / 3);
  };
  const std::vector<std::array<VertexId, 2>> traces = Traces(crack);
  ASSERT_EQ(traces.size(), 3u);
  const Eigen::Vector4d free = ConeApexWeights(crack, rest);
  const Eigen::Vector3d hole = middle_of(free, traces[0]);
  const double radius = 0.005;
  const ApexNearPath outside_the_hole = [&](const Eigen::Vector4d& w) {
    return (at(w) - hole).norm() > radius;
  };
  ASSERT_TRUE(outside_the_hole(free));
  const Eigen::Vector4d chosen = ConeApexWeights(crack, rest, outside_the_hole);
  EXPECT_GT((chosen - free).norm(), 1e-6);
  for (const auto& s : traces) EXPECT_GT((middle_of(chosen, s) - hole).norm(), radius);
  EXPECT_GE(chosen.minCoeff(), kApexMargin - 1e-12);
}

// Where the blade's path comes near no candidate on the traces' plane (it went by the tet's corner
// 0, the crack's plane cutting off corner 3), the points where it went are tried, pulled inside by
// kOnPathApexMargin: the apex is near the path, and the points are asked for only then.
TEST(ConeApex, WhereNoCandidateIsNearThePathTheApexIsWhereTheBladeWent) {
  OneTet tet = CornerThreeCutOff();
  const TetCrack crack = tet.Crack();
  const auto rest = tet.RestOf();
  const Eigen::Vector4d went(0.86, 0.06, 0.04, 0.04);
  // Pulled inside by kOnPathApexMargin, `went` moves about 0.2 (by kApexMargin, 0.35).
  const ApexNearPath near_corner = [&](const Eigen::Vector4d& w) {
    return (w - went).norm() < 0.25;
  };
  int asked = 0;
  const ApexOnPath on_path = [&] {
    ++asked;
    return std::vector<Eigen::Vector4d>{Eigen::Vector4d::Constant(0.25), went};
  };
  const Eigen::Vector4d chosen = ConeApexWeights(crack, rest, near_corner, on_path);
  EXPECT_EQ(asked, 1);
  EXPECT_TRUE(near_corner(chosen));
  EXPECT_GE(chosen.minCoeff(), kOnPathApexMargin - 1e-12);
  EXPECT_LT(chosen.minCoeff(), kApexMargin);
  // Without them, no candidate is near: the apex is the plane's, off the path.
  EXPECT_FALSE(near_corner(ConeApexWeights(crack, rest, near_corner)));
  // Where a candidate on the plane is near, they are not asked for.
  ConeApexWeights(
      crack, rest, [](const Eigen::Vector4d&) { return true; }, on_path);
  EXPECT_EQ(asked, 1);
}

}  // namespace
}  // namespace kerf::cut
