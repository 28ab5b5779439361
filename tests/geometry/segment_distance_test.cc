#include "geometry/segment_distance.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kerf::geometry {
namespace {

const Eigen::Vector3d kP(0, 0, 0), kQ(2, 0, 0);

TEST(DistanceToSegment, BesideTheMiddleIsThePerpendicular) {
  EXPECT_DOUBLE_EQ(DistanceToSegment({1, 3, 4}, kP, kQ), 5);
  EXPECT_DOUBLE_EQ(DistanceToSegment({0.5, 0, 0}, kP, kQ), 0);  // on it
}

TEST(DistanceToSegment, PastAnEndIsToThatEnd) {
  EXPECT_DOUBLE_EQ(DistanceToSegment({-3, 4, 0}, kP, kQ), 5);
  EXPECT_DOUBLE_EQ(DistanceToSegment({5, 0, 4}, kP, kQ), 5);
}

TEST(DistanceToSegment, APointSegmentIsItsPoint) {
  EXPECT_DOUBLE_EQ(DistanceToSegment({0, 3, 4}, kP, kP), 5);
}

TEST(ClosestPointsOfSegments, CrossingSegmentsMeet) {
  const ClosestPoints c = ClosestPointsOfSegments(kP, kQ, {0.5, -1, 0}, {0.5, 3, 0});
  EXPECT_DOUBLE_EQ(c.s, 0.25);
  EXPECT_DOUBLE_EQ(c.t, 0.25);
  EXPECT_DOUBLE_EQ(c.distance, 0);
}

TEST(ClosestPointsOfSegments, SkewSegmentsAreTheirCommonPerpendicularApart) {
  const ClosestPoints c = ClosestPointsOfSegments(kP, kQ, {1.5, -1, 2}, {1.5, 1, 2});
  EXPECT_DOUBLE_EQ(c.s, 0.75);
  EXPECT_DOUBLE_EQ(c.t, 0.5);
  EXPECT_DOUBLE_EQ(c.distance, 2);
}

TEST(ClosestPointsOfSegments, EndsClampAndParallelsGiveAPair) {
  const ClosestPoints past = ClosestPointsOfSegments(kP, kQ, {3, 1, 0}, {3, 5, 0});
  EXPECT_DOUBLE_EQ(past.s, 1);
  EXPECT_DOUBLE_EQ(past.t, 0);
  EXPECT_DOUBLE_EQ(past.distance, std::sqrt(2.0));
  const ClosestPoints parallel = ClosestPointsOfSegments(kP, kQ, {1, 3, 0}, {5, 3, 0});
  EXPECT_DOUBLE_EQ(parallel.distance, 3);
}

}  // namespace
}  // namespace kerf::geometry
