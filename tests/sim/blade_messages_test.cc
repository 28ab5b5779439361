#include "sim/blade_messages.h"

#include <gtest/gtest.h>

#include "support/status_message.h"

namespace kerf::sim {
namespace {

using cut::BladePose;
using kerf::testing::StatusMessage;

constexpr char kPath[] = R"({"poses": [
  {"time": 0.0, "tip": [0.0, 0.0, 0.01], "heel": [0.0, 0.0, 0.03]},
  {"time": 0.01, "tip": [0.002, 0.0, 0.01], "heel": [0.002, 0.0, 0.03]}
]})";

TEST(ParseBladePathJson, ReadsPoses) {
  absl::StatusOr<std::vector<BladePose>> path = ParseBladePathJson(kPath, "p.json", {});
  ASSERT_TRUE(path.ok()) << path.status();
  ASSERT_EQ(path->size(), 2u);
  EXPECT_EQ((*path)[1].time, 0.01);
  EXPECT_EQ((*path)[1].tip, Eigen::Vector3d(0.002, 0, 0.01));
  EXPECT_EQ((*path)[1].heel, Eigen::Vector3d(0.002, 0, 0.03));
}

TEST(ParseBladePathJson, RefusesBadPathsNamingThePose) {
  EXPECT_EQ(StatusMessage(ParseBladePathJson("{\"poses\": []}", "p.json", {})),
            "p.json: the path has no poses");
  EXPECT_EQ(StatusMessage(ParseBladePathJson(
                R"({"poses": [{"time": 0, "tip": [0, 0], "heel": [0, 0, 1]}]})", "p.json", {})),
            "p.json: pose 0: tip and heel must be [x, y, z]; got 2 and 3 numbers");
  EXPECT_EQ(
      StatusMessage(ParseBladePathJson(R"({"poses": [{"time": 0, "knife": 1}]})", "p.json", {})),
      "p.json: not a blade path ((poses[0]) knife: Cannot find field.)");
  EXPECT_EQ(StatusMessage(ParseBladePathJson(
                R"({"poses": [{"time": 0, "tip": [0, 0, 0], "heel": [0, 0, 0.02]},
                              {"time": 0, "tip": [0, 0, 0], "heel": [0, 0, 0.02]}]})",
                "p.json", {})),
            "p.json: pose 1: time 0 s does not follow the previous pose's 0 s");
}

TEST(BladePoseMessages, RoundTripExactly) {
  const BladePose pose{0.125, {0.1, -0.2, 1.0 / 3}, {0.7, 1e-300, -5}};
  absl::StatusOr<BladePose> back = BladePoseFromProto(BladePoseToProto(pose));
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->time, pose.time);
  EXPECT_EQ(back->tip, pose.tip);
  EXPECT_EQ(back->heel, pose.heel);
}

}  // namespace
}  // namespace kerf::sim
