// Starts a gRPC server for the Simulator service the way kerf-server runs it: standard health
// checking, server reflection, keepalive and a cap on request size.
#pragma once

#include <grpcpp/grpcpp.h>

#include <memory>
#include <string>

#include "absl/status/statusor.h"

namespace kerf::service {

struct ServerConfig {
  std::string listen = "127.0.0.1:50051";  // host:port; port 0 picks a free one
  int max_message_bytes = 4 << 20;         // largest request accepted
  // TLS: PEM files of the server's certificate chain and private key. Both or neither.
  std::string tls_certificate_file;
  std::string tls_key_file;
  // Plaintext is served only on a loopback address unless this is set.
  bool allow_remote_plaintext = false;
};

// Plaintext on 127.0.0.1 at a free port: for tests and local runs.
inline ServerConfig LoopbackConfig() {
  ServerConfig config;
  config.listen = "127.0.0.1:0";
  return config;
}

// Whether `listen`'s host is a loopback address (127.0.0.0/8, ::1 or localhost).
bool IsLoopback(const std::string& listen);

struct RunningServer {
  std::unique_ptr<grpc::Server> server;
  int port = 0;  // the port it listens on
};

// INVALID_ARGUMENT for plaintext on a non-loopback address (unless allowed), for only one of
// the TLS files, or for one that cannot be read; UNAVAILABLE naming the address when it cannot
// listen.
absl::StatusOr<RunningServer> StartServer(const ServerConfig& config, grpc::Service* service);

}  // namespace kerf::service
