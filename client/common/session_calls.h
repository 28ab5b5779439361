// The calls every client makes around its work: making a session and closing it.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "kerf/v1/simulator.grpc.pb.h"

namespace kerf::client {

// A session of the embedded scene `scene_name` (empty: the server's default), within 10 s.
// The gRPC error, as a status whose message starts "CreateSession: ".
absl::StatusOr<kerf::v1::CreateSessionResponse> CreateSession(kerf::v1::Simulator::Stub& stub,
                                                              const std::string& scene_name);

// Closes a session with its cutter token; its final state and counts. The error as above.
absl::StatusOr<kerf::v1::SessionInfo> CloseSession(kerf::v1::Simulator::Stub& stub,
                                                   const std::string& session_id,
                                                   const std::string& cutter_token);

}  // namespace kerf::client
