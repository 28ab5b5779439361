#include "cut/cut_statistics.h"

#include <gtest/gtest.h>

namespace kerf::cut {
namespace {

TEST(ProgressiveCase, FollowsTableOne) {
  EXPECT_EQ(ProgressiveCase(0, 1, 1, true, false), 1);
  EXPECT_EQ(ProgressiveCase(0, 2, 2, false, false), 2);
  EXPECT_EQ(ProgressiveCase(1, 0, 2, false, false), 3);
  EXPECT_EQ(ProgressiveCase(1, 1, 1, true, false), 4);
  EXPECT_EQ(ProgressiveCase(1, 2, 2, false, false), 5);
  EXPECT_EQ(ProgressiveCase(2, 0, 2, false, true), 6);
  EXPECT_EQ(ProgressiveCase(2, 1, 1, true, true), 7);
  EXPECT_EQ(ProgressiveCase(2, 2, 2, false, true), 8);
  EXPECT_EQ(ProgressiveCase(2, 2, 2, false, false), 9);
  EXPECT_EQ(ProgressiveCase(3, 0, 2, false, false), 10);
  EXPECT_EQ(ProgressiveCase(3, 1, 1, true, false), 11);
  EXPECT_EQ(ProgressiveCase(0, 0, 2, false, false), 0);
  EXPECT_EQ(ProgressiveCase(4, 0, 2, false, false), 0);
}

}  // namespace
}  // namespace kerf::cut
