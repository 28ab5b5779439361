#include "common/session_calls.h"

#include <chrono>

#include "absl/strings/str_cat.h"

namespace kerf::client {
namespace {

absl::Status Failed(const char* call, const grpc::Status& status) {
  return absl::Status(static_cast<absl::StatusCode>(status.error_code()),
                      absl::StrCat(call, ": ", status.error_message()));
}

}  // namespace

absl::StatusOr<kerf::v1::CreateSessionResponse> CreateSession(kerf::v1::Simulator::Stub& stub,
                                                              const std::string& scene_name) {
  kerf::v1::CreateSessionRequest request;
  request.set_scene_name(scene_name);
  kerf::v1::CreateSessionResponse created;
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  const grpc::Status status = stub.CreateSession(&context, request, &created);
  if (!status.ok()) return Failed("CreateSession", status);
  return created;
}

absl::StatusOr<kerf::v1::SessionInfo> CloseSession(kerf::v1::Simulator::Stub& stub,
                                                   const std::string& session_id,
                                                   const std::string& cutter_token) {
  kerf::v1::CloseSessionRequest request;
  request.set_session_id(session_id);
  request.set_token(cutter_token);
  kerf::v1::CloseSessionResponse closed;
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  const grpc::Status status = stub.CloseSession(&context, request, &closed);
  if (!status.ok()) return Failed("CloseSession", status);
  return closed.session();
}

}  // namespace kerf::client
