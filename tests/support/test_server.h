// A kerf gRPC server on loopback (ephemeral port) for tests, with a client's stub, and the
// tokens of the sessions it made.
#pragma once

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <string>

#include "absl/strings/str_cat.h"
#include "absl/synchronization/mutex.h"
#include "kerf/v1/simulator.grpc.pb.h"
#include "service/grpc_server.h"
#include "service/simulator_service.h"
#include "sim/scene.h"
#include "support/service_bar.h"

namespace kerf::testing {

// The tokens of the sessions the tests made, by session id.
struct Tokens {
  std::string cutter, observer;
};
inline Tokens& TokensOf(const std::string& session) {
  static absl::Mutex mutex(absl::kConstInit);
  static auto* tokens = new std::map<std::string, Tokens>;
  absl::MutexLock lock(&mutex);
  return (*tokens)[session];
}

class Server {
 public:
  explicit Server(service::RegistryOptions options = {})
      : registry_(std::move(options)), service_(&registry_) {
    absl::StatusOr<service::RunningServer> running =
        service::StartServer(service::LoopbackConfig(), &service_);
    EXPECT_TRUE(running.ok()) << running.status();
    server_ = std::move(running->server);
    port_ = running->port;
    channel_ =
        grpc::CreateChannel(absl::StrCat("127.0.0.1:", port_), grpc::InsecureChannelCredentials());
    stub_ = kerf::v1::Simulator::NewStub(channel_);
  }
  ~Server() {
    registry_.CloseAll(absl::UnavailableError("test over"));
    server_->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
  }
  kerf::v1::Simulator::Stub& stub() { return *stub_; }
  grpc::Channel& channel() { return *channel_; }
  int port() const { return port_; }

  kerf::v1::SessionInfo CreateBarSession(double frame_rate_hz = 0,
                                         const char* scene = kServiceBarScene) {
    kerf::v1::CreateSessionRequest request;
    request.set_frame_rate_hz(frame_rate_hz);
    *request.mutable_scene() = *sim::ParseSceneText(scene, "test");
    kerf::v1::CreateSessionResponse created;
    grpc::ClientContext context;
    const grpc::Status status = stub_->CreateSession(&context, request, &created);
    EXPECT_TRUE(status.ok()) << status.error_message();
    TokensOf(created.session().session_id()) = {created.cutter_token(), created.observer_token()};
    return created.session();
  }

 private:
  service::SessionRegistry registry_;
  service::SimulatorService service_;
  int port_ = 0;
  std::unique_ptr<grpc::Server> server_;
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<kerf::v1::Simulator::Stub> stub_;
};

inline kerf::v1::Frame Snapshot(Server& server, const std::string& session, kerf::v1::Level level) {
  kerf::v1::GetSnapshotRequest request;
  request.set_session_id(session);
  request.set_level(level);
  request.set_token(TokensOf(session).observer);
  kerf::v1::Frame snapshot;
  grpc::ClientContext context;
  const grpc::Status status = server.stub().GetSnapshot(&context, request, &snapshot);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return snapshot;
}

// The session as ListSessions shows it.
inline kerf::v1::SessionInfo Listed(Server& server, const std::string& id) {
  kerf::v1::ListSessionsResponse sessions;
  grpc::ClientContext context;
  EXPECT_TRUE(server.stub().ListSessions(&context, {}, &sessions).ok());
  for (const kerf::v1::SessionInfo& s : sessions.sessions()) {
    if (s.session_id() == id) return s;
  }
  ADD_FAILURE() << "no session " << id;
  return {};
}

}  // namespace kerf::testing
