// Samples of the blade's steps inside a tet, and how far a crack leaves them (cut/steps_in_tet.h).
#include "cut/steps_in_tet.h"

#include <gtest/gtest.h>

namespace kerf::cut {
namespace {

const std::array<Eigen::Vector3d, 4> kUnitTet = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                                 Eigen::Vector3d(0, 1, 0),
                                                 Eigen::Vector3d(0, 0, 1)};

// A blade standing through the tet, moved across it: every sample lies inside, on the blade's
// sweep (the plane y = 0.2, here), and a step beside the tet gives none.
TEST(StepSamplesIn, SamplesLieInsideTheTetOnTheSweep) {
  SweptPath path(100);
  path.Add({0, {-0.5, 0.2, -1}, {-0.5, 0.2, 2}});
  path.Add({1, {0.5, 0.2, -1}, {0.5, 0.2, 2}});
  path.Add({2, {3, 0.2, -1}, {3, 0.2, 2}});
  path.Add({3, {4, 0.2, -1}, {4, 0.2, 2}});  // the step from 3 to 4 misses the tet
  const std::vector<Eigen::Vector4d> first = StepSamplesIn(kUnitTet, path, 1, 2);
  ASSERT_GT(first.size(), 3u);
  for (const Eigen::Vector4d& w : first) {
    EXPECT_GE(w.minCoeff(), 0);
    EXPECT_NEAR(w.sum(), 1, 1e-12);
    EXPECT_NEAR(PointAtWeights(kUnitTet, w).y(), 0.2, 1e-12);
  }
  EXPECT_EQ(StepSamplesIn(kUnitTet, path, 3, 4).size(), 0u);
}

// A blade held in the tet for 1,000 steps: no more than kSampledSteps of them are sampled.
TEST(StepSamplesIn, ALongStayIsSampledAtKSampledStepsSteps) {
  SweptPath path(2000);
  for (int i = 0; i <= 1000; ++i) {
    const double x = 0.1 + 0.0001 * i;
    path.Add({0.001 * i, {x, 0.2, -1}, {x, 0.2, 2}});
  }
  const std::vector<Eigen::Vector4d> samples = StepSamplesIn(kUnitTet, path, 1, 1001);
  EXPECT_GT(samples.size(), std::size_t{kSampledSteps});
  EXPECT_LE(samples.size(), std::size_t{3 * kBladeSamples * kSampledSteps});
}

// Samples 0.1, 0.3 and 0.5 above the triangle z = 0: with a reach of 0.2 two lie beyond it, the
// farthest at 0.5; with no triangle every sample lies beyond.
TEST(StepSamplesIn, MeasureCountsTheSamplesBeyondTheReach) {
  const std::vector<Eigen::Vector4d> samples = {Eigen::Vector4d(0.7, 0.1, 0.1, 0.1),
                                                Eigen::Vector4d(0.5, 0.1, 0.1, 0.3),
                                                Eigen::Vector4d(0.3, 0.1, 0.1, 0.5)};
  const std::vector<std::array<Eigen::Vector3d, 3>> floor = {
      {kUnitTet[0], kUnitTet[1], kUnitTet[2]}};
  const SamplesFrom from = Measure(samples, kUnitTet, floor, 0.2);
  EXPECT_EQ(from.beyond, 2);
  EXPECT_NEAR(from.distance, 0.5, 1e-12);
  EXPECT_EQ(from.farthest, samples[2]);
  EXPECT_EQ(Measure(samples, kUnitTet, {}, 0.2).beyond, 3);
}

// A blade leaning by 4e-17 m along x over its 3 m (a fuzzed pose stream's), beside the tet: the
// first of its samples in the tet's box would lie 5e15 samples along it, so none is (that count,
// cast to an int, once started a loop over 2^31 samples); moved into the tet, it is sampled
// inside only.
TEST(StepSamplesIn, ABladeAlmostAlongAnAxisBesideTheTetIsSampledOnlyInside) {
  const Eigen::Vector3d tip(-0.01, 0.2, -1), along = Eigen::Vector3d(4e-17, 0, 3) / 20;
  const auto [first, last] =
      SamplesInBox(tip, along, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  EXPECT_GT(first, last);
  EXPECT_GE(first, 0);
  SweptPath path(10);
  path.Add({0, tip, tip + 20 * along});
  path.Add({1, {0.01, 0.2, -1}, {0.01 + 4e-17, 0.2, 2}});
  const std::vector<Eigen::Vector4d> samples = StepSamplesIn(kUnitTet, path, 1, 2);
  EXPECT_FALSE(samples.empty());
  for (const Eigen::Vector4d& w : samples) EXPECT_GE(PointAtWeights(kUnitTet, w).x(), 0);
}

// Whether a sample at the blade's tip lies inside: a blade standing with its tip in the tet, and
// one standing through it with its tip below.
TEST(StepSamplesIn, TellsWhetherTheTipWentThroughTheTet) {
  for (const double tip_z : {0.1, -1.0}) {
    SweptPath path(8);
    path.Add({0, {-0.5, 0.2, tip_z}, {-0.5, 0.2, 2}});
    path.Add({1, {1.5, 0.2, tip_z}, {1.5, 0.2, 2}});
    bool tip_inside = tip_z < 0;  // set whatever it held
    EXPECT_FALSE(StepSamplesIn(kUnitTet, path, 1, 2, &tip_inside).empty());
    EXPECT_EQ(tip_inside, tip_z > 0) << "tip at z = " << tip_z;
  }
}

// At most the bound, from the first, evenly: of 100, every seventh (15); of fewer, all.
TEST(SpreadEvenly, KeepsAtMostTheBoundFromTheFirst) {
  std::vector<Eigen::Vector4d> samples;
  for (int i = 0; i < 100; ++i) samples.push_back(Eigen::Vector4d(i, 0, 0, 0));
  const std::vector<Eigen::Vector4d> spread = SpreadEvenly(samples, 16);
  ASSERT_EQ(spread.size(), 15u);
  for (std::size_t k = 0; k < spread.size(); ++k) EXPECT_EQ(spread[k][0], 7.0 * k);
  EXPECT_EQ(SpreadEvenly({samples.begin(), samples.begin() + 5}, 16).size(), 5u);
  EXPECT_TRUE(SpreadEvenly({}, 16).empty());
}

}  // namespace
}  // namespace kerf::cut
