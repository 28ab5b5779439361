// Session: what a session does with a cut the simulation refuses (the gRPC face of sessions is
// tested against a real server in simulator_service_test.cc).
#include "service/session.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "absl/synchronization/notification.h"
#include "sim/scene.h"

namespace kerf::service {
namespace {

using ::testing::HasSubstr;

constexpr char kBarScene[] = R"pb(
  name: "test-bar"
  mesh {
    lattice {
      cells_x: 4
      cells_y: 2
      cells_z: 2
      size { x: 0.04 y: 0.02 z: 0.02 }
    }
  }
  material { youngs_modulus: 5000 poisson_ratio: 0.45 density: 1000 mass_damping: 20 }
)pb";

kerf::v1::BladePose Pose(double time, double y) {
  kerf::v1::BladePose pose;
  pose.set_time(time);
  for (const double c : {0.0237, y, -0.005}) pose.add_tip(c);
  for (const double c : {0.0237, y, 0.025}) pose.add_heel(c);
  return pose;
}

TEST(Session, APoseTheSimulationRefusesEndsTheCutWithWhyAndTheSessionGoesOn) {
  absl::StatusOr<sim::Scene> scene = sim::BuildScene(*sim::ParseSceneText(kBarScene, "test"), ".");
  ASSERT_TRUE(scene.ok()) << scene.status();
  // BuildScene refuses this fraction; a scene built in code meets it first when the cutter is
  // made, at the blade's first pose.
  scene->snap_fraction = 0.7;
  absl::StatusOr<std::unique_ptr<Session>> session =
      Session::Create({.id = "refusing",
                       .scene = *std::move(scene),
                       .tokens = SessionTokens::Generate().first,
                       .journal = nullptr,
                       .recorded = {},
                       .catch_up_to_tick = 0},
                      {});
  ASSERT_TRUE(session.ok()) << session.status();

  absl::Notification ended;
  absl::Status why;
  absl::StatusOr<std::shared_ptr<Subscription>> cutter = (*session)->BeginCut(
      kerf::v1::FORCES, 0, [](const SerializedFrame&) {},
      [&](const absl::Status& s) {
        why = s;
        ended.Notify();
      });
  ASSERT_TRUE(cutter.ok()) << cutter.status();
  ASSERT_TRUE((*session)->SubmitPose(Pose(0, 0.005)).ok());
  ASSERT_TRUE(ended.WaitForNotificationWithTimeout(absl::Seconds(20)))
      << "the cutter's stream was not ended";
  EXPECT_EQ(why.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(why.message(), HasSubstr("the snap fraction must be in [0, 0.5), got 0.7"));
  EXPECT_THAT(why.message(), HasSubstr("the cut is ended and the blade withdrawn"));

  // The blade is free, and a pose without a cut is refused as such.
  EXPECT_FALSE((*session)->Info().cutting());
  EXPECT_EQ((*session)->SubmitPose(Pose(0.01, 0.005)).code(),
            absl::StatusCode::kFailedPrecondition);
  const double time = (*session)->Info().simulation_time();
  absl::SleepFor(absl::Milliseconds(50));
  EXPECT_GT((*session)->Info().simulation_time(), time) << "the session stopped";
}

}  // namespace
}  // namespace kerf::service
