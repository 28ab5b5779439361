#include "geometry/segment_box.h"

#include <gtest/gtest.h>

namespace kerf::geometry {
namespace {

const Eigen::Vector3d kLo(0, 0, 0), kHi(1, 2, 3);

TEST(SegmentMeetsBox, ThroughInsideAndTouching) {
  EXPECT_TRUE(SegmentMeetsBox({-1, 1, 1}, {2, 1, 1}, kLo, kHi, 0));             // through
  EXPECT_TRUE(SegmentMeetsBox({0.5, 0.5, 0.5}, {0.6, 0.6, 0.6}, kLo, kHi, 0));  // inside
  EXPECT_TRUE(SegmentMeetsBox({-1, 1, 1}, {0, 1, 1}, kLo, kHi, 0));             // ends on a face
  EXPECT_TRUE(SegmentMeetsBox({1, 2, -1}, {1, 2, 5}, kLo, kHi, 0));             // along an edge
  EXPECT_TRUE(SegmentMeetsBox({-1, -1, 0}, {1, 1, 0}, kLo, kHi, 0));            // through a corner
}

TEST(SegmentMeetsBox, ShortOfBesideAndPast) {
  EXPECT_FALSE(SegmentMeetsBox({-2, 1, 1}, {-0.1, 1, 1}, kLo, kHi, 0));     // stops short
  EXPECT_FALSE(SegmentMeetsBox({-1, 2.1, 1}, {2, 2.1, 1}, kLo, kHi, 0));    // parallel, beside
  EXPECT_FALSE(SegmentMeetsBox({-1, 0, 3.5}, {3, 4, 3.5}, kLo, kHi, 0));    // above
  EXPECT_FALSE(SegmentMeetsBox({-1, 1.5, 0}, {0.5, 3.5, 0}, kLo, kHi, 0));  // misses a corner
}

TEST(SegmentMeetsBox, AMarginWidensTheBox) {
  EXPECT_FALSE(SegmentMeetsBox({-1, 2.1, 1}, {2, 2.1, 1}, kLo, kHi, 0.05));
  EXPECT_TRUE(SegmentMeetsBox({-1, 2.1, 1}, {2, 2.1, 1}, kLo, kHi, 0.2));
}

}  // namespace
}  // namespace kerf::geometry
