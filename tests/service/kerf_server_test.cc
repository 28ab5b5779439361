// The kerf-server binary as an operator runs it: it starts with no scene arguments, serves,
// and on SIGTERM ends every stream with UNAVAILABLE and exits 0.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <csignal>
#include <cstdio>
#include <string>

#include "absl/strings/ascii.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "kerf/v1/simulator.grpc.pb.h"

namespace kerf::service {
namespace {

TEST(KerfServer, ServesAndShutsDownGracefullyOnSigterm) {
  // The shell prints its pid and becomes the server (exec keeps the pid).
  FILE* out = popen(absl::StrCat("sh -c 'echo $$; exec ", KERF_SERVER_BINARY,
                                 " --listen=127.0.0.1:0 --max_sessions=2'")
                        .c_str(),
                    "r");
  ASSERT_NE(out, nullptr);
  char line[256];
  ASSERT_NE(fgets(line, sizeof(line), out), nullptr);
  int pid = 0;
  ASSERT_TRUE(absl::SimpleAtoi(absl::StripAsciiWhitespace(line), &pid)) << line;
  ASSERT_NE(fgets(line, sizeof(line), out), nullptr);
  const std::string started = line;  // "kerf-server listening on 127.0.0.1:PORT"
  const std::size_t colon = started.rfind(':');
  int port = 0;
  ASSERT_TRUE(absl::SimpleAtoi(absl::StripAsciiWhitespace(started.substr(colon + 1)), &port))
      << started;

  auto stub = kerf::v1::Simulator::NewStub(
      grpc::CreateChannel(absl::StrCat("127.0.0.1:", port), grpc::InsecureChannelCredentials()));
  kerf::v1::CreateSessionResponse created;
  {
    grpc::ClientContext context;
    ASSERT_TRUE(stub->CreateSession(&context, {}, &created).ok());  // the default scene
  }
  const kerf::v1::SessionInfo& info = created.session();
  EXPECT_EQ(info.scene_name(), "lattice-tension");
  EXPECT_EQ(info.tets(), 576u);
  grpc::ClientContext observe_context;
  kerf::v1::ObserveRequest request;
  request.set_session_id(info.session_id());
  request.set_level(kerf::v1::SURFACE);
  request.set_token(created.observer_token());
  auto reader = stub->Observe(&observe_context, request);
  kerf::v1::Frame frame;
  ASSERT_TRUE(reader->Read(&frame));
  EXPECT_TRUE(frame.keyframe());

  ASSERT_EQ(kill(pid, SIGTERM), 0);
  while (reader->Read(&frame)) {
  }
  const grpc::Status status = reader->Finish();
  EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_EQ(status.error_message(), "the server is shutting down");
  std::string rest;
  while (fgets(line, sizeof(line), out) != nullptr) rest += line;
  const int exit_status = pclose(out);
  EXPECT_TRUE(WIFEXITED(exit_status) && WEXITSTATUS(exit_status) == 0) << rest;
}

}  // namespace
}  // namespace kerf::service
