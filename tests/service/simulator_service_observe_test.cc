// The service end to end, what observers see: frames that rebuild what a snapshot shows, for
// observers early, late, slow or stuck, on a real gRPC server on loopback.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "service/simulator_service.h"
#include "support/cut_streams.h"
#include "support/frame_observer.h"
#include "support/test_server.h"

namespace kerf::service {
namespace {

using kerf::testing::CutAcross;
using kerf::testing::ExpectSeesSnapshot;
using kerf::testing::Observer;
using kerf::testing::Server;
using kerf::testing::Snapshot;
using kerf::testing::TokensOf;
using kerf::v1::Frame;

TEST(SimulatorService, ObserversAtEveryLevelRebuildWhatTheSnapshotShows) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  ASSERT_FALSE(info.session_id().empty());
  EXPECT_EQ(info.tets(), 4u * 2 * 2 * 6);
  std::vector<std::unique_ptr<Observer>> observers;
  const kerf::v1::Level levels[] = {kerf::v1::SURFACE, kerf::v1::VOLUME, kerf::v1::FORCES};
  for (const kerf::v1::Level level : levels) {
    for (int i = 0; i < 3; ++i) {
      observers.push_back(std::make_unique<Observer>(server.stub(), info.session_id(), level));
    }
  }
  int cutter_frames = 0;
  double largest_force = 0;
  std::uint64_t poses_applied = 0;
  const grpc::Status cut =
      CutAcross(server.stub(), info.session_id(), &cutter_frames, &largest_force, &poses_applied);
  ASSERT_TRUE(cut.ok()) << cut.error_message();
  EXPECT_GT(cutter_frames, 5);
  // The cutter felt the tissue: at least the cutting resistance of 100 N/m over the bar's
  // 2 cm depth (2 N) while the blade moved through it.
  EXPECT_GT(largest_force, 1.0);
  // 16 poses over 150 ms at 1 kHz ticks: interpolated poses in between.
  EXPECT_GT(poses_applied, 100u);
  absl::SleepFor(absl::Milliseconds(100));  // the blade is withdrawn, the cut opens
  for (int l = 0; l < 3; ++l) {
    const Frame snapshot = Snapshot(server, info.session_id(), levels[l]);
    if (levels[l] == kerf::v1::VOLUME) {
      EXPECT_GT(snapshot.added_elements_size(), static_cast<int>(info.tets()));  // it is cut
    }
    if (levels[l] == kerf::v1::SURFACE) {  // the cut's faces are marked
      EXPECT_NE(snapshot.added_elements_on_cut().find('\x01'), std::string::npos);
    }
    for (int i = 0; i < 3; ++i) ExpectSeesSnapshot(*observers[3 * l + i], snapshot);
  }
}

TEST(SimulatorService, SnapshotsAtAChosenFrameNumber) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  const Frame now = Snapshot(server, info.session_id(), kerf::v1::SURFACE);
  const auto at = [&](std::uint64_t sequence, Frame* frame) {
    kerf::v1::GetSnapshotRequest request;
    request.set_session_id(info.session_id());
    request.set_level(kerf::v1::SURFACE);
    request.set_token(TokensOf(info.session_id()).observer);
    request.set_sequence(sequence);
    grpc::ClientContext context;
    return server.stub().GetSnapshot(&context, request, frame);
  };
  Frame later;
  const grpc::Status waited = at(now.sequence() + 5, &later);
  ASSERT_TRUE(waited.ok()) << waited.error_message();
  EXPECT_EQ(later.sequence(), now.sequence() + 5);
  // Frame n is due at the tick where n frames per (physics/frame rate) ticks are done.
  EXPECT_NEAR(later.simulation_time() - now.simulation_time(), 5.0 / 60, 1.5e-3);
  EXPECT_EQ(later.model_sha256().size(), 32u);
  Frame none;
  const grpc::Status past = at(now.sequence(), &none);
  EXPECT_EQ(past.error_code(), grpc::StatusCode::OUT_OF_RANGE);
  EXPECT_NE(past.error_message().find("the session has made"), std::string::npos)
      << past.error_message();
  EXPECT_EQ(at(later.sequence() + 3600 + 60, &none).error_code(),
            grpc::StatusCode::OUT_OF_RANGE);  // more than a minute ahead
}

TEST(SimulatorService, AnObserverPastItsDeadlineIsDropped) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::milliseconds(200));
  kerf::v1::ObserveRequest request;
  request.set_session_id(info.session_id());
  request.set_level(kerf::v1::SURFACE);
  request.set_token(TokensOf(info.session_id()).observer);
  auto reader = server.stub().Observe(&context, request);
  Frame frame;
  int frames = 0;
  while (reader->Read(&frame)) ++frames;
  EXPECT_GT(frames, 0);
  EXPECT_EQ(reader->Finish().error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
  int observers = -1;
  for (int wait = 0; wait < 100 && observers != 0; ++wait) {
    kerf::v1::ListSessionsResponse sessions;
    grpc::ClientContext list_context;
    ASSERT_TRUE(server.stub().ListSessions(&list_context, {}, &sessions).ok());
    observers = static_cast<int>(sessions.sessions(0).observers());
    absl::SleepFor(absl::Milliseconds(10));
  }
  EXPECT_EQ(observers, 0);
}

TEST(SimulatorService, ALateJoinerStartsFromAKeyframeOfTheCutMesh) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  int frames = 0;
  ASSERT_TRUE(CutAcross(server.stub(), info.session_id(), &frames).ok());
  Observer late(server.stub(), info.session_id(), kerf::v1::VOLUME);
  const Frame snapshot = Snapshot(server, info.session_id(), kerf::v1::VOLUME);
  EXPECT_GT(snapshot.added_elements_size(), static_cast<int>(info.tets()));  // it is cut
  ExpectSeesSnapshot(late, snapshot);
  EXPECT_TRUE(late.first_was_keyframe());
}

TEST(SimulatorService, ASlowObserverSkipsPositionsButLosesNoTopology) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession(500);
  // The slow observer's channel takes 8 kB at a time (a few frames; no window growth), and
  // it does not read for a second: the server's writes to it stall while frames come at 500 Hz.
  grpc::ChannelArguments narrow;
  narrow.SetInt(GRPC_ARG_HTTP2_STREAM_LOOKAHEAD_BYTES, 8192);
  narrow.SetInt(GRPC_ARG_HTTP2_BDP_PROBE, 0);
  const auto slow_stub = kerf::v1::Simulator::NewStub(grpc::CreateCustomChannel(
      absl::StrCat("127.0.0.1:", server.port()), grpc::InsecureChannelCredentials(), narrow));
  Observer prompt(server.stub(), info.session_id(), kerf::v1::VOLUME);
  Observer slow(*slow_stub, info.session_id(), kerf::v1::VOLUME, absl::Seconds(1));
  int frames = 0;
  ASSERT_TRUE(CutAcross(server.stub(), info.session_id(), &frames).ok());
  absl::SleepFor(absl::Seconds(1));
  const Frame snapshot = Snapshot(server, info.session_id(), kerf::v1::VOLUME);
  EXPECT_GT(snapshot.added_elements_size(), static_cast<int>(info.tets()));
  ExpectSeesSnapshot(prompt, snapshot);
  ExpectSeesSnapshot(slow, snapshot);
  EXPECT_GT(slow.gaps() + slow.keyframes() - 1, 0) << "the slow observer was never behind";
  EXPECT_EQ(prompt.keyframes(), 1);
}

TEST(SimulatorService, ObserverLimitIsResourceExhausted) {
  RegistryOptions options;
  options.session.max_subscribers = 2;
  Server server(options);
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  Observer a(server.stub(), info.session_id(), kerf::v1::SURFACE);
  Observer b(server.stub(), info.session_id(), kerf::v1::VOLUME);
  ExpectSeesSnapshot(b, Snapshot(server, info.session_id(), kerf::v1::VOLUME));
  Observer c(server.stub(), info.session_id(), kerf::v1::FORCES);
  const std::optional<grpc::Status> end = c.EndStatus();
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(end->error_message(),
            absl::StrCat("session ", info.session_id(), " has its limit of 2 observers"));
}

}  // namespace
}  // namespace kerf::service
