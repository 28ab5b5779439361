#include "service/session_registry.h"

#include <algorithm>

#include "absl/random/random.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"

namespace kerf::service {
namespace {

std::string NewSessionId() {
  static absl::Mutex mutex(absl::kConstInit);
  static absl::BitGen* bits = new absl::BitGen;
  absl::MutexLock lock(&mutex);
  return absl::StrFormat("%016x%016x", absl::Uniform<std::uint64_t>(*bits),
                         absl::Uniform<std::uint64_t>(*bits));
}

absl::StatusOr<sim::Scene> SceneOf(const kerf::v1::CreateSessionRequest& request,
                                   const RegistryOptions& options) {
  const std::string& default_scene = options.default_scene;
  if (request.has_scene()) {
    if (request.scene().mesh().has_file()) {
      return absl::InvalidArgumentError(
          "scene.mesh.file: the server reads no files for a client; send a lattice or use an "
          "embedded scene");
    }
    // Checked before anything is built: a client must not make the server run out of memory.
    const kerf::v1::BoxLattice& lattice = request.scene().mesh().lattice();
    const double tets = 6.0 * std::max(lattice.cells_x(), 0) * std::max(lattice.cells_y(), 0) *
                        std::max(lattice.cells_z(), 0);
    if (tets > static_cast<double>(options.max_scene_tets)) {
      return absl::ResourceExhaustedError(
          absl::StrFormat("scene.mesh.lattice: %.0f tets is over this server's limit of %d", tets,
                          options.max_scene_tets));
    }
    return sim::BuildScene(request.scene(), ".");
  }
  const std::string name = request.scene_name().empty() ? default_scene : request.scene_name();
  const std::vector<std::string> names = sim::EmbeddedSceneNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    return absl::NotFoundError(
        absl::StrCat("no scene named '", name, "'; the server has: ", absl::StrJoin(names, ", ")));
  }
  return sim::LoadScene(name);
}

}  // namespace

absl::StatusOr<std::shared_ptr<Session>> SessionRegistry::Create(
    const kerf::v1::CreateSessionRequest& request) {
  {
    absl::MutexLock lock(&mutex_);
    if (sessions_.size() >= options_.max_sessions) {
      return absl::ResourceExhaustedError(absl::StrCat(
          "the server holds its limit of ", options_.max_sessions, " sessions; close one first"));
    }
  }
  absl::StatusOr<sim::Scene> scene = SceneOf(request, options_);
  if (!scene.ok()) return scene.status();
  SessionOptions session_options = options_.session;
  if (request.physics_rate_hz() != 0) session_options.physics_rate_hz = request.physics_rate_hz();
  if (request.frame_rate_hz() != 0) session_options.frame_rate_hz = request.frame_rate_hz();
  absl::StatusOr<std::unique_ptr<Session>> session =
      Session::Create(NewSessionId(), *std::move(scene), session_options);
  if (!session.ok()) return session.status();
  std::shared_ptr<Session> shared = *std::move(session);
  absl::MutexLock lock(&mutex_);
  if (sessions_.size() >= options_.max_sessions) {  // others were made meanwhile
    return absl::ResourceExhaustedError(absl::StrCat(
        "the server holds its limit of ", options_.max_sessions, " sessions; close one first"));
  }
  sessions_[shared->id()] = shared;
  return shared;
}

absl::StatusOr<std::shared_ptr<Session>> SessionRegistry::Find(const std::string& id) const {
  absl::MutexLock lock(&mutex_);
  const auto it = sessions_.find(id);
  if (it == sessions_.end()) return absl::NotFoundError(absl::StrCat("no session '", id, "'"));
  return it->second;
}

absl::Status SessionRegistry::Close(const std::string& id) {
  std::shared_ptr<Session> session;
  {
    absl::MutexLock lock(&mutex_);
    const auto it = sessions_.find(id);
    if (it == sessions_.end()) return absl::NotFoundError(absl::StrCat("no session '", id, "'"));
    session = std::move(it->second);
    sessions_.erase(it);
  }
  session->Close(absl::CancelledError(absl::StrCat("session ", id, " was closed")));
  return absl::OkStatus();
}

void SessionRegistry::CloseAll(const absl::Status& why) {
  absl::flat_hash_map<std::string, std::shared_ptr<Session>> sessions;
  {
    absl::MutexLock lock(&mutex_);
    sessions.swap(sessions_);
  }
  for (auto& [id, session] : sessions) session->Close(why);
}

std::vector<std::shared_ptr<Session>> SessionRegistry::List() const {
  absl::MutexLock lock(&mutex_);
  std::vector<std::shared_ptr<Session>> list;
  for (const auto& [id, session] : sessions_) list.push_back(session);
  std::sort(list.begin(), list.end(),
            [](const auto& a, const auto& b) { return a->id() < b->id(); });
  return list;
}

}  // namespace kerf::service
