// Starts a gRPC server for the Simulator service the way kerf-server runs it: standard health
// checking, server reflection, keepalive and a cap on request size.
#pragma once

#include <memory>
#include <string>

#include <grpcpp/grpcpp.h>

#include "absl/status/statusor.h"

namespace kerf::service {

struct ServerConfig {
  std::string listen = "127.0.0.1:50051";  // host:port; port 0 picks a free one
  int max_message_bytes = 4 << 20;         // largest request accepted
};

struct RunningServer {
  std::unique_ptr<grpc::Server> server;
  int port = 0;  // the port it listens on
};

// UNAVAILABLE naming the address when it cannot listen.
absl::StatusOr<RunningServer> StartServer(const ServerConfig& config, grpc::Service* service);

}  // namespace kerf::service
