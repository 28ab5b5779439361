#include "geometry/moving_crossing.h"

#include <gtest/gtest.h>

#include <random>

#include "geometry/segment_triangle_intersection.h"

namespace kerf::geometry {
namespace {

using Eigen::Vector3d;

Motion Still(const Vector3d& x) { return {x, x}; }
Motion By(const Vector3d& x, const Vector3d& d) { return {x, x + d}; }

TEST(FirstEdgeCrossing, AnEdgeMovingAcrossAStillBlade) {
  // The blade lies along z at x = 0; the edge (along y, at x = -0.3) moves +x by 1.
  const Vector3d d(1, 0, 0);
  const auto hit = FirstEdgeCrossing(By({-0.3, -1, 0.5}, d), By({-0.3, 3, 0.5}, d),
                                     Still({0, 0, 0}), Still({0, 0, 2}));
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->time, 0.3, 1e-12);
  EXPECT_NEAR(hit->fraction, 0.25, 1e-12);
  EXPECT_NEAR(hit->along, 0.25, 1e-12);
  // Moving the other way, or not far enough, it never meets the blade.
  EXPECT_FALSE(FirstEdgeCrossing(By({-0.3, -1, 0.5}, -d), By({-0.3, 3, 0.5}, -d), Still({0, 0, 0}),
                                 Still({0, 0, 2})));
  EXPECT_FALSE(FirstEdgeCrossing(By({-0.3, -1, 0.5}, 0.2 * d), By({-0.3, 3, 0.5}, 0.2 * d),
                                 Still({0, 0, 0}), Still({0, 0, 2})));
}

TEST(FirstEdgeCrossing, OnlyRelativeMotionCounts) {
  // The same meeting seen from a frame moving with the edge: the blade moves instead.
  const Vector3d d(1, 0, 0);
  const auto tissue_moves = FirstEdgeCrossing(By({-0.3, -1, 0.5}, d), By({-0.3, 3, 0.5}, d),
                                              Still({0, 0, 0}), Still({0, 0, 2}));
  const auto blade_moves = FirstEdgeCrossing(Still({-0.3, -1, 0.5}), Still({-0.3, 3, 0.5}),
                                             By({0, 0, 0}, -d), By({0, 0, 2}, -d));
  ASSERT_TRUE(tissue_moves && blade_moves);
  EXPECT_NEAR(tissue_moves->time, blade_moves->time, 1e-12);
  EXPECT_NEAR(tissue_moves->fraction, blade_moves->fraction, 1e-12);
  // Both moving alike: they never meet.
  EXPECT_FALSE(FirstEdgeCrossing(By({-0.3, -1, 0.5}, d), By({-0.3, 3, 0.5}, d), By({0, 0, 0}, d),
                                 By({0, 0, 2}, d)));
}

TEST(FirstEdgeCrossing, OnStillTissueItAgreesWithTheSweptTriangles) {
  // A blade translating over still tissue sweeps a flat quad: the crossing is where the two
  // triangles of the swept surface are crossed.
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  int compared = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vector3d a(unit(random), unit(random), unit(random));
    const Vector3d b(unit(random), unit(random), unit(random));
    const Vector3d p(unit(random), unit(random), unit(random));
    const Vector3d q(unit(random), unit(random), unit(random));
    const Vector3d d(unit(random), unit(random), unit(random));
    const auto moving = FirstEdgeCrossing(Still(a), Still(b), By(p, d), By(q, d));
    auto swept = IntersectSegmentTriangle(a, b, p, q, q + d);
    if (!swept) swept = IntersectSegmentTriangle(a, b, p, q + d, p + d);
    ASSERT_EQ(moving.has_value(), swept.has_value()) << "trial " << trial;
    if (!moving) continue;
    EXPECT_NEAR(moving->fraction, swept->t, 1e-9) << "trial " << trial;
    ++compared;
  }
  EXPECT_GT(compared, 100);
}

TEST(FirstEdgeCrossing, AMeetingAtTheStartBelongsToThePreviousInterval) {
  // The edge touches the blade at time 0 and moves away.
  EXPECT_FALSE(FirstEdgeCrossing(By({0, -1, 0.5}, {1, 0, 0}), By({0, 1, 0.5}, {1, 0, 0}),
                                 Still({0, 0, 0}), Still({0, 0, 1})));
  // It reaches the blade exactly at time 1: that interval's.
  const auto end = FirstEdgeCrossing(By({-1, -1, 0.5}, {1, 0, 0}), By({-1, 1, 0.5}, {1, 0, 0}),
                                     Still({0, 0, 0}), Still({0, 0, 1}));
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->time, 1.0);
}

TEST(FirstEdgeCrossing, ParallelOrCoplanarGivesNothing) {
  // Parallel to the blade and crossing its line's plane: the lines never meet.
  EXPECT_FALSE(FirstEdgeCrossing(By({-1, 0, 0}, {2, 0, 0}), By({-1, 0, 1}, {2, 0, 0}),
                                 Still({0, 0, 0}), Still({0, 0, 1})));
  // Still, in the blade's plane.
  EXPECT_FALSE(FirstEdgeCrossing(Still({-1, 0, 0.5}), Still({1, 0, 0.5}), Still({0, 0, 0}),
                                 Still({0, 0, 1})));
}

TEST(FirstPointCrossing, AFaceMovingOntoAStillTip) {
  // Triangle in z = -0.5 moving +z by 1; the tip is still at (0.2, 0.3, 0).
  const Vector3d d(0, 0, 1);
  const auto hit = FirstPointCrossing(Still({0.2, 0.3, 0}), By({0, 0, -0.5}, d),
                                      By({1, 0, -0.5}, d), By({0, 1, -0.5}, d));
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->time, 0.5, 1e-12);
  EXPECT_TRUE(hit->barycentric.isApprox(Vector3d(0.5, 0.2, 0.3), 1e-12)) << hit->barycentric;
  // Beside the triangle, it misses.
  EXPECT_FALSE(FirstPointCrossing(Still({0.8, 0.8, 0}), By({0, 0, -0.5}, d), By({1, 0, -0.5}, d),
                                  By({0, 1, -0.5}, d)));
}

TEST(FirstPointCrossing, OnStillTissueItAgreesWithTheSegmentTest) {
  std::mt19937 random(9);
  std::uniform_real_distribution<double> unit(-1, 1);
  int compared = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vector3d a(unit(random), unit(random), unit(random));
    const Vector3d b(unit(random), unit(random), unit(random));
    const Vector3d c(unit(random), unit(random), unit(random));
    const Vector3d p(unit(random), unit(random), unit(random));
    const Vector3d q(unit(random), unit(random), unit(random));
    const auto moving = FirstPointCrossing({p, q}, Still(a), Still(b), Still(c));
    const auto segment = IntersectSegmentTriangle(p, q, a, b, c);
    ASSERT_EQ(moving.has_value(), segment.has_value()) << "trial " << trial;
    if (!moving) continue;
    EXPECT_NEAR(moving->time, segment->t, 1e-9) << "trial " << trial;
    EXPECT_TRUE(moving->barycentric.isApprox(segment->barycentric, 1e-8)) << "trial " << trial;
    ++compared;
  }
  EXPECT_GT(compared, 100);
}

}  // namespace
}  // namespace kerf::geometry
