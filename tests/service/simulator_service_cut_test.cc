// The service end to end, the cutter's stream: one cutter at a time, poses ahead of the
// session, a cutter that vanishes, on a real gRPC server on loopback.
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
using kerf::testing::CutStart;
using kerf::testing::CutWith;
using kerf::testing::ExpectSeesSnapshot;
using kerf::testing::Listed;
using kerf::testing::Observer;
using kerf::testing::Pose;
using kerf::testing::Server;
using kerf::testing::Snapshot;
using kerf::testing::TokensOf;
using kerf::v1::Frame;

TEST(SimulatorService, PosesFarAheadOfTheSessionAreRefused) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  // The second pose is 5 s later on the client's clock, sent at once.
  const grpc::Status status =
      CutWith(server.stub(), info.session_id(), TokensOf(info.session_id()).cutter,
              {Pose(0, -0.005), Pose(5, -0.004)});
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(status.error_message().find("send poses in real time"), std::string::npos)
      << status.error_message();
}

TEST(SimulatorService, ACutterThatDisconnectsMidCutLeavesAWorkingSession) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  Observer observer(server.stub(), info.session_id(), kerf::v1::VOLUME);
  {
    grpc::ClientContext context;
    auto stream = server.stub().Cut(&context);
    stream->Write(CutStart(info.session_id(), TokensOf(info.session_id()).cutter));
    for (int k = 0; k <= 8; ++k) {  // the blade stops inside the bar
      kerf::v1::CutRequest request;
      *request.mutable_pose() = Pose(0.01 * k, -0.005 + 0.002 * k);
      stream->Write(request);
    }
    absl::SleepFor(absl::Milliseconds(50));
    context.TryCancel();  // gone, without a word
    Frame frame;
    while (stream->Read(&frame)) {
    }
  }
  // The blade is withdrawn and free again; everything observed still adds up.
  for (int wait = 0; wait < 100; ++wait) {
    kerf::v1::ListSessionsResponse sessions;
    grpc::ClientContext context;
    ASSERT_TRUE(server.stub().ListSessions(&context, {}, &sessions).ok());
    ASSERT_EQ(sessions.sessions_size(), 1);
    if (!sessions.sessions(0).cutting()) break;
    absl::SleepFor(absl::Milliseconds(10));
  }
  int frames = 0;
  EXPECT_TRUE(CutAcross(server.stub(), info.session_id(), &frames).ok());
  ExpectSeesSnapshot(observer, Snapshot(server, info.session_id(), kerf::v1::VOLUME));
}

// A cutter that vanishes with poses queued ahead of the session: they are dropped with it, its
// blade comes out, and the next cutter's blade cuts from its own first pose (the next cut's poses
// were once queued behind the vanished one's and refused by the cutter, without a word).
TEST(SimulatorService, TheNextCutterCutsThoughTheLastLeftPosesQueued) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  {
    grpc::ClientContext context;
    auto stream = server.stub().Cut(&context);
    stream->Write(CutStart(info.session_id(), TokensOf(info.session_id()).cutter));
    for (int k = 0; k < 150; ++k) {  // 1.5 s of a blade held still beside the bar
      kerf::v1::CutRequest request;
      *request.mutable_pose() = Pose(0.01 * k, -0.005);
      stream->Write(request);
    }
    Frame frame;
    ASSERT_TRUE(stream->Read(&frame));  // the session took the cut
    context.TryCancel();
    while (stream->Read(&frame)) {
    }
  }
  for (int wait = 0; wait < 100; ++wait) {
    if (!Listed(server, info.session_id()).cutting()) break;
    absl::SleepFor(absl::Milliseconds(10));
  }
  int frames = 0;
  const grpc::Status cut = CutAcross(server.stub(), info.session_id(), &frames);
  ASSERT_TRUE(cut.ok()) << cut.error_message();
  EXPECT_GT(Listed(server, info.session_id()).tets(), info.tets()) << "the second cut cut nothing";
}

TEST(SimulatorService, OneCutterAtATime) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  grpc::ClientContext first_context;
  auto first = server.stub().Cut(&first_context);
  const kerf::v1::CutRequest start =
      CutStart(info.session_id(), TokensOf(info.session_id()).cutter);
  first->Write(start);
  Frame frame;
  ASSERT_TRUE(first->Read(&frame));  // the first cutter holds the blade
  grpc::ClientContext second_context;
  auto second = server.stub().Cut(&second_context);
  second->Write(start);
  second->WritesDone();
  while (second->Read(&frame)) {
  }
  const grpc::Status status = second->Finish();
  EXPECT_EQ(status.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_EQ(status.error_message(),
            absl::StrCat("session ", info.session_id(), " already has a cutter; one at a time"));
  first->WritesDone();
  while (first->Read(&frame)) {
  }
  EXPECT_TRUE(first->Finish().ok());
}

}  // namespace
}  // namespace kerf::service
