// The blade's recent poses and the steps near a box (cut/swept_path.h).
#include "cut/swept_path.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace kerf::cut {
namespace {

BladePose PoseAt(double t, const Eigen::Vector3d& tip) {
  return {t, tip, tip + Eigen::Vector3d(0, 0, 0.1)};
}

// Poses are numbered from 1; past the capacity the oldest go.
TEST(SweptPath, KeepsTheLastPosesNumberedAsTheyCame) {
  SweptPath path(3);
  EXPECT_LT(path.last(), path.first());
  for (int i = 1; i <= 5; ++i) path.Add(PoseAt(i, Eigen::Vector3d(i, 0, 0)));
  EXPECT_EQ(path.first(), 3u);
  EXPECT_EQ(path.last(), 5u);
  EXPECT_EQ(path.at(4).tip.x(), 4);
}

// A wandering path of 1,000 poses kept 300 at a time: the steps near a box are those, and only
// those, a test of every step's box finds, in order; a visit that returns false stops the walk.
TEST(SweptPath, FindsTheStepsNearABoxAsTestingEveryStepWould) {
  std::mt19937_64 random(7);
  std::normal_distribution<double> jitter(0, 0.05);
  SweptPath path(300);
  std::vector<BladePose> all = {PoseAt(0, Eigen::Vector3d::Zero())};
  path.Add(all.back());
  for (int i = 1; i < 1000; ++i) {
    all.push_back(PoseAt(
        i, all.back().tip + Eigen::Vector3d(jitter(random), jitter(random), jitter(random))));
    path.Add(all.back());
  }
  ASSERT_EQ(path.last(), 1000u);
  ASSERT_EQ(path.first(), 701u);
  const Eigen::Vector3d low = all[850].tip, high = low + Eigen::Vector3d::Constant(0.1);
  const double reach = 0.02;
  std::vector<std::size_t> expected;
  for (std::size_t i = 701; i < 1000; ++i) {
    const BladePose& a = all[i - 1];
    const BladePose& b = all[i];
    const Eigen::Vector3d step_low = a.tip.cwiseMin(a.heel).cwiseMin(b.tip).cwiseMin(b.heel);
    const Eigen::Vector3d step_high = a.tip.cwiseMax(a.heel).cwiseMax(b.tip).cwiseMax(b.heel);
    if (((step_low.array() - reach) <= high.array()).all() &&
        ((step_high.array() + reach) >= low.array()).all()) {
      expected.push_back(i);
    }
  }
  ASSERT_GT(expected.size(), 2u);
  ASSERT_LT(expected.size(), 299u);
  std::vector<std::size_t> found;
  path.ForEachStepNear(0, 2000, low, high, reach, [&](std::size_t i) {
    found.push_back(i);
    return true;
  });
  EXPECT_EQ(found, expected);
  found.clear();
  path.ForEachStepNear(0, 2000, low, high, reach, [&](std::size_t i) {
    found.push_back(i);
    return found.size() < 2;
  });
  EXPECT_EQ(found, std::vector<std::size_t>(expected.begin(), expected.begin() + 2));
}

}  // namespace
}  // namespace kerf::cut
