// The service end to end, its sessions and the gRPC service itself: a real gRPC server on
// loopback (ephemeral port) and real clients (observers in simulator_service_observe_test.cc,
// cutters in simulator_service_cut_test.cc).
#include "service/simulator_service.h"

#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <set>

#include "absl/strings/str_cat.h"
#include "absl/synchronization/notification.h"
#include "sim/scene.h"
#include "support/cut_streams.h"
#include "support/frame_observer.h"
#include "support/service_bar.h"
#include "support/test_server.h"

namespace kerf::service {
namespace {

using kerf::testing::CutAcross;
using kerf::testing::CutWith;
using kerf::testing::ExpectSeesSnapshot;
using kerf::testing::Observer;
using kerf::testing::Pose;
using kerf::testing::Server;
using kerf::testing::Snapshot;
using kerf::testing::Tokens;
using kerf::testing::TokensOf;
using kerf::v1::Frame;

constexpr const char* kBarScene = kerf::testing::kServiceBarScene;

TEST(SimulatorService, ListsScenesAndSessionsAndMakesSessionsByName) {
  Server server;
  kerf::v1::ListScenesResponse scenes;
  {
    grpc::ClientContext context;
    ASSERT_TRUE(server.stub().ListScenes(&context, {}, &scenes).ok());
  }
  std::set<std::string> names;
  for (const auto& scene : scenes.scenes()) {
    names.insert(scene.name());
    EXPECT_FALSE(scene.description().empty()) << scene.name();
  }
  EXPECT_EQ(names, (std::set<std::string>{"bar-cantilever", "lattice-tension",
                                          "lattice-tension-deferred"}));
  kerf::v1::CreateSessionRequest request;
  request.set_scene_name("bar-cantilever");
  kerf::v1::CreateSessionResponse created;
  {
    grpc::ClientContext context;
    ASSERT_TRUE(server.stub().CreateSession(&context, request, &created).ok());
  }
  const kerf::v1::SessionInfo& info = created.session();
  TokensOf(info.session_id()) = {created.cutter_token(), created.observer_token()};
  EXPECT_EQ(info.scene_name(), "bar-cantilever");
  EXPECT_EQ(info.levels_size(), 2);  // the scene needs SURFACE and VOLUME only
  kerf::v1::ListSessionsResponse sessions;
  grpc::ClientContext context;
  ASSERT_TRUE(server.stub().ListSessions(&context, {}, &sessions).ok());
  ASSERT_EQ(sessions.sessions_size(), 1);
  EXPECT_EQ(sessions.sessions(0).session_id(), info.session_id());
  // A level the scene does not offer is refused.
  Observer forces(server.stub(), info.session_id(), kerf::v1::FORCES);
  const std::optional<grpc::Status> end = forces.EndStatus();
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_EQ(end->error_message(), "scene bar-cantilever does not offer FORCES");
}

TEST(SimulatorService, TokensGrantTheirRolesOnly) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  const kerf::v1::SessionInfo other = server.CreateBarSession();
  const Tokens tokens = TokensOf(info.session_id());
  EXPECT_EQ(tokens.cutter.size(), 64u);
  EXPECT_EQ(tokens.observer.size(), 64u);
  EXPECT_NE(tokens.cutter, tokens.observer);
  EXPECT_NE(tokens.cutter, TokensOf(other.session_id()).cutter);
  const auto observe_with = [&](const std::string& token) {
    grpc::ClientContext context;
    kerf::v1::ObserveRequest request;
    request.set_session_id(info.session_id());
    request.set_level(kerf::v1::SURFACE);
    request.set_token(token);
    auto reader = server.stub().Observe(&context, request);
    Frame frame;
    if (reader->Read(&frame)) {  // served: that is all this wants to know
      context.TryCancel();
      while (reader->Read(&frame)) {
      }
      (void)reader->Finish();
      return grpc::Status::OK;
    }
    return reader->Finish();
  };
  EXPECT_EQ(observe_with("").error_code(), grpc::StatusCode::UNAUTHENTICATED);
  const grpc::Status wrong = observe_with(TokensOf(other.session_id()).observer);
  EXPECT_EQ(wrong.error_code(), grpc::StatusCode::PERMISSION_DENIED);
  EXPECT_EQ(wrong.error_message(), "the token does not belong to this session");
  EXPECT_TRUE(observe_with(tokens.observer).ok());
  EXPECT_TRUE(observe_with(tokens.cutter).ok());
  {  // the observer token cannot cut
    const grpc::Status status = CutWith(server.stub(), info.session_id(), tokens.observer, {});
    EXPECT_EQ(status.error_code(), grpc::StatusCode::PERMISSION_DENIED);
    EXPECT_EQ(status.error_message(), "the observer token cannot cut or close");
  }
  for (const std::string& token : {std::string(), tokens.observer}) {  // nor close
    kerf::v1::CloseSessionRequest request;
    request.set_session_id(info.session_id());
    request.set_token(token);
    kerf::v1::CloseSessionResponse response;
    grpc::ClientContext context;
    EXPECT_EQ(
        server.stub().CloseSession(&context, request, &response).error_code(),
        token.empty() ? grpc::StatusCode::UNAUTHENTICATED : grpc::StatusCode::PERMISSION_DENIED);
  }
  // Listing sessions shows no token.
  kerf::v1::ListSessionsResponse sessions;
  grpc::ClientContext context;
  ASSERT_TRUE(server.stub().ListSessions(&context, {}, &sessions).ok());
  const std::string listed = sessions.SerializeAsString();
  EXPECT_EQ(listed.find(tokens.cutter), std::string::npos);
  EXPECT_EQ(listed.find(tokens.observer), std::string::npos);
}

TEST(SimulatorService, BadInputGetsAClearErrorAndTheSessionGoesOn) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  {  // unknown session
    kerf::v1::GetSnapshotRequest request;
    request.set_session_id("nope");
    request.set_level(kerf::v1::SURFACE);
    Frame frame;
    grpc::ClientContext context;
    const grpc::Status status = server.stub().GetSnapshot(&context, request, &frame);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND);
    EXPECT_EQ(status.error_message(), "no session 'nope'");
  }
  {  // unknown scene
    kerf::v1::CreateSessionRequest request;
    request.set_scene_name("liver-of-nobody");
    kerf::v1::CreateSessionResponse created;
    grpc::ClientContext context;
    const grpc::Status status = server.stub().CreateSession(&context, request, &created);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND);
  }
  {  // a malformed scene
    kerf::v1::CreateSessionRequest request;
    *request.mutable_scene() = *sim::ParseSceneText(kBarScene, "test");
    request.mutable_scene()->mutable_material()->set_poisson_ratio(0.7);
    kerf::v1::CreateSessionResponse created;
    grpc::ClientContext context;
    const grpc::Status status = server.stub().CreateSession(&context, request, &created);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(status.error_message().find("poisson_ratio"), std::string::npos)
        << status.error_message();
  }
  {  // a lattice that would not fit in memory, refused before anything is built
    kerf::v1::CreateSessionRequest request;
    *request.mutable_scene() = *sim::ParseSceneText(kBarScene, "test");
    request.mutable_scene()->mutable_mesh()->mutable_lattice()->set_cells_x(1000);
    request.mutable_scene()->mutable_mesh()->mutable_lattice()->set_cells_y(1000);
    request.mutable_scene()->mutable_mesh()->mutable_lattice()->set_cells_z(1000);
    kerf::v1::CreateSessionResponse created;
    grpc::ClientContext context;
    const grpc::Status status = server.stub().CreateSession(&context, request, &created);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
    EXPECT_EQ(status.error_message(),
              "scene.mesh.lattice: 6000000000 tets is over this server's limit of 2000000");
  }
  const std::string& cutter = TokensOf(info.session_id()).cutter;
  {  // a NaN pose ends the cut stream with INVALID_ARGUMENT
    const grpc::Status status =
        CutWith(server.stub(), info.session_id(), cutter, {Pose(0, std::nan(""))});
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  }
  {  // a blade that teleports 5 cm between poses 10 ms apart
    const grpc::Status status =
        CutWith(server.stub(), info.session_id(), cutter, {Pose(0, -0.005), Pose(0.01, 0.045)});
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(status.error_message().find("jumps"), std::string::npos) << status.error_message();
  }
  // The session is unharmed: a proper cut follows.
  int frames = 0;
  EXPECT_TRUE(CutAcross(server.stub(), info.session_id(), &frames).ok());
  EXPECT_GT(frames, 0);
}

TEST(SimulatorService, ClosingASessionEndsItsStreams) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  Observer observer(server.stub(), info.session_id(), kerf::v1::SURFACE);
  ExpectSeesSnapshot(observer, Snapshot(server, info.session_id(), kerf::v1::SURFACE));
  kerf::v1::CloseSessionRequest request;
  request.set_session_id(info.session_id());
  request.set_token(TokensOf(info.session_id()).cutter);
  kerf::v1::CloseSessionResponse response;
  grpc::ClientContext context;
  ASSERT_TRUE(server.stub().CloseSession(&context, request, &response).ok());
  const std::optional<grpc::Status> end = observer.EndStatus();
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->error_code(), grpc::StatusCode::CANCELLED);
  EXPECT_EQ(end->error_message(), absl::StrCat("session ", info.session_id(), " was closed"));
  kerf::v1::ListSessionsResponse sessions;
  grpc::ClientContext list_context;
  ASSERT_TRUE(server.stub().ListSessions(&list_context, {}, &sessions).ok());
  EXPECT_EQ(sessions.sessions_size(), 0);
}

TEST(SimulatorService, AnswersStandardHealthChecks) {
  Server server;
  grpc::GenericStub generic(std::shared_ptr<grpc::Channel>(&server.channel(), [](auto*) {}));
  grpc::ClientContext context;
  grpc::Slice empty{std::string()};  // an empty HealthCheckRequest: the whole server
  grpc::ByteBuffer request(&empty, 1), response;
  absl::Notification done;
  grpc::Status status;
  generic.UnaryCall(&context, "/grpc.health.v1.Health/Check", grpc::StubOptions(), &request,
                    &response, [&](grpc::Status s) {
                      status = s;
                      done.Notify();
                    });
  done.WaitForNotification();
  ASSERT_TRUE(status.ok()) << status.error_message();
  std::vector<grpc::Slice> slices;
  ASSERT_TRUE(response.Dump(&slices).ok());
  std::string bytes;
  for (const grpc::Slice& slice : slices) {
    bytes.append(reinterpret_cast<const char*>(slice.begin()), slice.size());
  }
  EXPECT_EQ(bytes, std::string("\x08\x01", 2));  // HealthCheckResponse{status: SERVING}
}

TEST(SimulatorService, ListsItsServicesThroughReflection) {
  Server server;
  grpc::GenericStub generic(std::shared_ptr<grpc::Channel>(&server.channel(), [](auto*) {}));
  // One ServerReflectionRequest{list_services: ""} on the bidirectional stream.
  class Reactor : public grpc::ClientBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer> {
   public:
    Reactor() : request_slice_(std::string("\x3a\x00", 2)), request_(&request_slice_, 1) {}
    void Start() {
      StartWrite(&request_);
      StartRead(&response_);
      StartWritesDone();
      StartCall();
    }
    void OnReadDone(bool ok) override {
      if (ok) {
        std::vector<grpc::Slice> slices;
        (void)response_.Dump(&slices);
        for (const grpc::Slice& s : slices) {
          bytes_.append(reinterpret_cast<const char*>(s.begin()), s.size());
        }
      }
    }
    void OnDone(const grpc::Status& status) override {
      status_ = status;
      done_.Notify();
    }
    std::string Wait() {
      done_.WaitForNotification();
      return status_.ok() ? bytes_ : status_.error_message();
    }

   private:
    grpc::Slice request_slice_;
    grpc::ByteBuffer request_, response_;
    std::string bytes_;
    grpc::Status status_;
    absl::Notification done_;
  } reactor;
  grpc::ClientContext context;
  generic.PrepareBidiStreamingCall(&context,
                                   "/grpc.reflection.v1alpha.ServerReflection/ServerReflectionInfo",
                                   grpc::StubOptions(), &reactor);
  reactor.Start();
  const std::string response = reactor.Wait();
  EXPECT_NE(response.find("kerf.v1.Simulator"), std::string::npos) << response;
  EXPECT_NE(response.find("grpc.health.v1.Health"), std::string::npos) << response;
}

TEST(SimulatorService, LimitsAreResourceExhausted) {
  RegistryOptions options;
  options.max_sessions = 1;
  Server server(options);
  server.CreateBarSession();
  kerf::v1::CreateSessionRequest request;
  *request.mutable_scene() = *sim::ParseSceneText(kBarScene, "test");
  kerf::v1::CreateSessionResponse created;
  grpc::ClientContext context;
  EXPECT_EQ(server.stub().CreateSession(&context, request, &created).error_code(),
            grpc::StatusCode::RESOURCE_EXHAUSTED);
}

TEST(SimulatorService, OversizedRequestsAreRefused) {
  Server server;  // the default cap: 4 MB
  kerf::v1::CreateSessionRequest request;
  *request.mutable_scene() = *sim::ParseSceneText(kBarScene, "test");
  request.mutable_scene()->set_description(std::string(5 << 20, 'x'));
  kerf::v1::CreateSessionResponse created;
  grpc::ClientContext context;
  const grpc::Status status = server.stub().CreateSession(&context, request, &created);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(status.error_message().find("message larger than max"), std::string::npos)
      << status.error_message();
}

}  // namespace
}  // namespace kerf::service
