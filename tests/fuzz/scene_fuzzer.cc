// Fuzz target for the scene a client sends: the input is a serialized
// kerf.v1.CreateSessionRequest, handed to a session registry as the service would hand it.
// Whatever it holds, the registry makes a session within its limits or refuses it with an
// error, never crashes, never reads a file and never builds more tets than its limit.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "google/protobuf/stubs/logging.h"
#include "service/session_registry.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
  static const bool quiet = (google::protobuf::SetLogHandler(nullptr), true);  // bad UTF-8 logs
  (void)quiet;
  kerf::v1::CreateSessionRequest request;
  if (!request.ParseFromArray(bytes, static_cast<int>(size))) return 0;  // gRPC refuses these
  kerf::service::RegistryOptions options;
  options.max_sessions = 1;
  options.max_scene_tets = 3000;  // small, so that each input is quick
  kerf::service::SessionRegistry registry(options);
  const absl::StatusOr<kerf::service::CreatedSession> created = registry.Create(request);
  if (!created.ok()) {
    if (created.status().message().empty()) std::abort();  // errors say what was wrong
    return 0;
  }
  if (request.scene().mesh().has_file()) std::abort();  // files are never read for a client
  const kerf::v1::SessionInfo info = created->session->Info();
  if (info.tets() == 0 || info.tets() > options.max_scene_tets) std::abort();
  registry.CloseAll(absl::CancelledError("fuzz input done"));
  return 0;
}
