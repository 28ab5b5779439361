// Fuzz target for a cutter's stream: the input is a sequence of kerf.v1.CutRequest messages,
// each preceded by its length (one byte), fed to a session of a small bar as the Cut stream
// feeds it (a start, then poses; anything else is refused as the service refuses it). The
// session runs a thousand times faster than real time. Whatever the stream holds, the session
// refuses what is bad with an error, withdraws the blade at the end, and leaves a valid mesh.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "absl/synchronization/notification.h"
#include "google/protobuf/stubs/logging.h"
#include "mesh/mesh_validation.h"
#include "service/session_registry.h"
#include "sim/scene.h"

namespace {

constexpr char kBar[] = R"pb(
  name: "bar"
  mesh {
    lattice {
      cells_x: 3
      cells_y: 2
      cells_z: 2
      size { x: 0.03 y: 0.02 z: 0.02 }
    }
  }
  material { youngs_modulus: 5000 poisson_ratio: 0.45 density: 1000 mass_damping: 20 }
  displacements {
    vertices {
      half_space {
        point { x: 0 }
        normal { x: -1 }
      }
    }
  }
  needs { levels: [ SURFACE, VOLUME, FORCES ] }
)pb";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
  static const bool quiet = (google::protobuf::SetLogHandler(nullptr), true);  // bad UTF-8 logs
  (void)quiet;
  static const kerf::v1::Scene* const scene =
      new kerf::v1::Scene(*kerf::sim::ParseSceneText(kBar, "bar"));
  kerf::service::RegistryOptions options;
  options.max_sessions = 1;
  options.session.speed = 1000;
  bool valid_at_end = true;
  options.session.after_tick = [&](std::uint64_t, double, const kerf::sim::Simulation& s) {
    valid_at_end = kerf::mesh::FindMeshDefects(s.mesh()).empty();
  };
  kerf::service::SessionRegistry registry(options);
  kerf::v1::CreateSessionRequest create;
  *create.mutable_scene() = *scene;
  const absl::StatusOr<kerf::service::CreatedSession> created = registry.Create(create);
  if (!created.ok()) std::abort();
  kerf::service::Session& session = *created->session;
  std::shared_ptr<kerf::service::Subscription> cut;
  for (std::size_t at = 0; at < size;) {
    const std::size_t length = bytes[at++];
    if (length > size - at) break;
    kerf::v1::CutRequest request;
    const bool parsed = request.ParseFromArray(bytes + at, static_cast<int>(length));
    at += length;
    if (!parsed) continue;
    if (request.has_start() && cut == nullptr) {
      absl::StatusOr<std::shared_ptr<kerf::service::Subscription>> begun = session.BeginCut(
          request.start().level(), request.start().frame_rate_hz(),
          [](const kerf::service::SerializedFrame&) {}, nullptr);
      if (begun.ok()) cut = *begun;
      continue;
    }
    if (request.has_pose() && cut != nullptr) {
      const absl::Status submitted = session.SubmitPose(request.pose());
      if (!submitted.ok() && submitted.message().empty()) std::abort();
    }
  }
  if (cut != nullptr) {
    absl::Notification withdrawn;
    session.EndCut([&] { withdrawn.Notify(); });
    if (!withdrawn.WaitForNotificationWithTimeout(absl::Seconds(30))) std::abort();
  }
  registry.CloseAll(absl::CancelledError("fuzz input done"));
  if (!valid_at_end) std::abort();
  return 0;
}
