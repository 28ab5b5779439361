// Session: what a session does with a cut the simulation refuses (the gRPC face of sessions is
// tested against a real server in simulator_service_test.cc).
#include "service/session.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <functional>

#include "absl/synchronization/mutex.h"
#include "absl/synchronization/notification.h"
#include "sim/scene.h"
#include "support/service_bar.h"

namespace kerf::service {
namespace {

using ::testing::HasSubstr;

using kerf::testing::BarBladePose;

// A session on the service tests' bar, with `adjust` applied to the built scene.
absl::StatusOr<std::unique_ptr<Session>> BarSession(
    const std::string& id, const SessionOptions& options,
    const std::function<void(sim::Scene&)>& adjust = nullptr) {
  absl::StatusOr<sim::Scene> scene =
      sim::BuildScene(*sim::ParseSceneText(kerf::testing::kServiceBarScene, "test"), ".");
  if (!scene.ok()) return scene.status();
  if (adjust) adjust(*scene);
  return Session::Create({.id = id,
                          .scene = *std::move(scene),
                          .tokens = SessionTokens::Generate().first,
                          .journal = nullptr,
                          .recorded = {},
                          .catch_up_to_tick = 0},
                         options);
}

TEST(Session, APoseTheSimulationRefusesEndsTheCutWithWhyAndTheSessionGoesOn) {
  // BuildScene refuses this fraction; a scene built in code meets it first when the cutter is
  // made, at the blade's first pose.
  absl::StatusOr<std::unique_ptr<Session>> session =
      BarSession("refusing", {}, [](sim::Scene& s) { s.snap_fraction = 0.7; });
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
  ASSERT_TRUE((*session)->SubmitPose(BarBladePose(0, 0.005)).ok());
  ASSERT_TRUE(ended.WaitForNotificationWithTimeout(absl::Seconds(20)))
      << "the cutter's stream was not ended";
  EXPECT_EQ(why.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(why.message(), HasSubstr("the snap fraction must be in [0, 0.5), got 0.7"));
  EXPECT_THAT(why.message(), HasSubstr("the cut is ended and the blade withdrawn"));

  // The blade is free, and a pose without a cut is refused as such.
  EXPECT_FALSE((*session)->Info().cutting());
  EXPECT_EQ((*session)->SubmitPose(BarBladePose(0.01, 0.005)).code(),
            absl::StatusCode::kFailedPrecondition);
  const double time = (*session)->Info().simulation_time();
  absl::SleepFor(absl::Milliseconds(50));
  EXPECT_GT((*session)->Info().simulation_time(), time) << "the session stopped";
}

// A hand trembling in the bar for a simulated minute, cutting progressively as it slowly
// advances: the mesh's change log keeps only what its readers have not read, however long the
// cut (each pose's temporary pieces add and remove tets: without trimming, the log held
// 3.5 million events by the end).
TEST(Session, ALongTremblingCutKeepsTheChangeLogBounded) {
  absl::Mutex mutex;
  std::size_t most_events = 0, ticks = 0;
  SessionOptions options;
  options.speed = 20;
  options.after_tick = [&](std::uint64_t, double, const sim::Simulation& s) {
    absl::MutexLock lock(&mutex);
    most_events = std::max(most_events, s.mesh().change_log().retained_events());
    ++ticks;
  };
  // The bar free, as cut here: nothing holds it.
  absl::StatusOr<std::unique_ptr<Session>> session =
      BarSession("trembling", options, [](sim::Scene& s) { s.conditions = {}; });
  ASSERT_TRUE(session.ok()) << session.status();
  std::atomic<bool> cutting = true;
  absl::StatusOr<std::shared_ptr<Subscription>> cutter = (*session)->BeginCut(
      kerf::v1::FORCES, 0, [](const SerializedFrame&) {},
      [&](const absl::Status& s) {
        if (cutting) ADD_FAILURE() << "the cut ended: " << s;
      });
  ASSERT_TRUE(cutter.ok()) << cutter.status();
  constexpr double kSeconds = 60, kRate = 200;  // poses per second
  for (int k = 0; k <= kSeconds * kRate; ++k) {
    const double t = k / kRate;
    // 1.5 cm into the bar's 4 cm over the minute, trembling 1 mm at 10 Hz across the cut.
    const double x = 0.005 + 0.015 * t / kSeconds + 0.001 * std::sin(2 * M_PI * 10 * t);
    const kerf::v1::BladePose pose = BarBladePose(t, 0.0103, x);
    while ((*session)->Info().simulation_time() + 1.0 < t) absl::SleepFor(absl::Milliseconds(5));
    ASSERT_TRUE((*session)->SubmitPose(pose).ok()) << "pose " << k;
  }
  while ((*session)->Info().simulation_time() < kSeconds + 0.5) {
    absl::SleepFor(absl::Milliseconds(20));
  }
  cutting = false;
  EXPECT_GT((*session)->Info().tets(), 96u) << "the blade cut nothing";
  absl::MutexLock lock(&mutex);
  EXPECT_GT(ticks, 60'000u);
  // A tick's own changes, at most: every reader has read the rest.
  EXPECT_LT(most_events, 2'000u);
}

}  // namespace
}  // namespace kerf::service
