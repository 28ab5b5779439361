// A channel to a kerf-server: plaintext, or TLS trusting the roots in a PEM file.
#pragma once

#include <grpcpp/grpcpp.h>

#include <memory>
#include <string>

#include "absl/status/statusor.h"

namespace kerf::client {

// `tls_ca` empty: plaintext. With `own_connection` the channel opens a connection of its own
// (as a separate client would) instead of sharing one with other channels to the same server.
// NOT_FOUND naming the file when the roots cannot be read.
absl::StatusOr<std::shared_ptr<grpc::Channel>> OpenChannel(const std::string& server,
                                                           const std::string& tls_ca,
                                                           bool own_connection = false);

}  // namespace kerf::client
