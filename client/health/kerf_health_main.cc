// kerf-health: asks a kerf-server's standard gRPC health service (grpc.health.v1.Health/Check)
// whether it is serving; exit status 0 when it is, 1 otherwise (with why). For container
// health checks and scripts.
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>

#include <cstdio>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/flags/usage.h"
#include "absl/synchronization/notification.h"
#include "common/channel.h"

ABSL_FLAG(std::string, server, "127.0.0.1:50051", "the kerf-server, host:port");
ABSL_FLAG(std::string, tls_ca, "", "PEM root certificate(s) to trust: TLS (plaintext when empty)");
ABSL_FLAG(double, timeout_seconds, 3, "how long to wait for the answer");
ABSL_FLAG(bool, wait, false,
          "wait (up to --timeout_seconds) for a server that is not listening yet, instead of "
          "failing at once: for scripts that start one");

int main(int argc, char** argv) {
  absl::SetProgramUsageMessage(
      "kerf-health [--server=HOST:PORT] [--tls_ca=CA.pem] [--timeout_seconds=S] [--wait]");
  absl::ParseCommandLine(argc, argv);
  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel =
      kerf::client::OpenChannel(absl::GetFlag(FLAGS_server), absl::GetFlag(FLAGS_tls_ca));
  if (!channel.ok()) {
    std::fprintf(stderr, "kerf-health: %s\n", std::string(channel.status().message()).c_str());
    return 1;
  }
  // HealthCheckRequest{service: ""} is the empty message; HealthCheckResponse{status: SERVING}
  // is field 1 = 1 (bytes 08 01). No generated code is needed for that.
  grpc::GenericStub stub(*channel);
  grpc::ClientContext context;
  context.set_wait_for_ready(absl::GetFlag(FLAGS_wait));
  context.set_deadline(
      std::chrono::system_clock::now() +
      std::chrono::milliseconds(static_cast<int>(1000 * absl::GetFlag(FLAGS_timeout_seconds))));
  grpc::ByteBuffer request, response;
  grpc::Slice empty("");
  request = grpc::ByteBuffer(&empty, 1);
  grpc::Status status;
  absl::Notification done;
  stub.UnaryCall(&context, "/grpc.health.v1.Health/Check", grpc::StubOptions(), &request, &response,
                 [&](grpc::Status s) {
                   status = std::move(s);
                   done.Notify();
                 });
  done.WaitForNotification();
  if (!status.ok()) {
    std::fprintf(stderr, "kerf-health: %s\n", status.error_message().c_str());
    return 1;
  }
  std::vector<grpc::Slice> slices;
  std::string bytes;
  if (response.Dump(&slices).ok()) {
    for (const grpc::Slice& s : slices)
      bytes.append(reinterpret_cast<const char*>(s.begin()), s.size());
  }
  if (bytes != std::string("\x08\x01", 2)) {
    std::fprintf(stderr, "kerf-health: not serving\n");
    return 1;
  }
  std::printf("SERVING\n");
  return 0;
}
