#include "service/session_registry.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

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

// The scene a request asks for, as a message (journaled as it is).
absl::StatusOr<kerf::v1::Scene> SpecOf(const kerf::v1::CreateSessionRequest& request,
                                       const RegistryOptions& options) {
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
    return request.scene();
  }
  const std::string name =
      request.scene_name().empty() ? options.default_scene : request.scene_name();
  const std::vector<std::string> names = sim::EmbeddedSceneNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    return absl::NotFoundError(
        absl::StrCat("no scene named '", name, "'; the server has: ", absl::StrJoin(names, ", ")));
  }
  absl::StatusOr<std::string> text = sim::EmbeddedSceneText(name);
  if (!text.ok()) return text.status();
  return sim::ParseSceneText(*text, name);
}

std::string JournalPath(const std::string& dir, const std::string& id) {
  return absl::StrCat(dir, "/", id, ".journal");
}

}  // namespace

absl::Status SessionRegistry::CheckRoom() const {
  if (sessions_.size() < options_.max_sessions) return absl::OkStatus();
  return absl::ResourceExhaustedError(absl::StrCat(
      "the server holds its limit of ", options_.max_sessions, " sessions; close one first"));
}

absl::Status SessionRegistry::Add(std::shared_ptr<Session> session) {
  absl::MutexLock lock(&mutex_);
  if (absl::Status s = CheckRoom(); !s.ok()) return s;
  sessions_[session->id()] = std::move(session);
  return absl::OkStatus();
}

absl::StatusOr<CreatedSession> SessionRegistry::Create(
    const kerf::v1::CreateSessionRequest& request) {
  {  // checked before anything is built, and again when it is added
    absl::MutexLock lock(&mutex_);
    if (absl::Status s = CheckRoom(); !s.ok()) return s;
  }
  absl::StatusOr<kerf::v1::Scene> spec = SpecOf(request, options_);
  if (!spec.ok()) return spec.status();
  absl::StatusOr<sim::Scene> scene = sim::BuildScene(*spec, ".");
  if (!scene.ok()) return scene.status();
  // The journal records what the session runs with, not what defaulted to it, so that a
  // replay means the same whatever the defaults become.
  spec->mutable_cutting()->set_mode(scene->cut_mode);
  spec->mutable_cutting()->set_min_temporary_height(scene->min_temporary_height);
  spec->mutable_cutting()->set_snap_fraction(scene->snap_fraction);
  spec->mutable_integration()->set_method(scene->method);
  spec->mutable_elasticity()->set_model(sim::ElasticityModelOf(scene->elastic.law));
  spec->mutable_elasticity()->set_auto_strain(scene->elastic.auto_strain);
  if (scene->sleep.has_value()) {
    kerf::v1::Sleeping* sleeping = spec->mutable_integration()->mutable_sleeping();
    sleeping->set_rest_speed(scene->sleep->rest_speed);
    sleeping->set_wake_acceleration(scene->sleep->wake_acceleration);
    sleeping->set_quiet_time(scene->sleep->quiet_time);
  }
  SessionOptions session_options = options_.session;
  if (request.physics_rate_hz() != 0) session_options.physics_rate_hz = request.physics_rate_hz();
  if (request.frame_rate_hz() != 0) session_options.frame_rate_hz = request.frame_rate_hz();
  auto [tokens, issued] = SessionTokens::Generate();
  SessionSetup setup{NewSessionId(), *std::move(scene), std::move(tokens), nullptr, {}, 0};
  if (!options_.journal_dir.empty()) {
    absl::StatusOr<std::unique_ptr<JournalWriter>> journal =
        JournalWriter::Open(JournalPath(options_.journal_dir, setup.id));
    if (!journal.ok()) return journal.status();
    kerf::v1::JournalRecord record;
    kerf::v1::JournalStart& start = *record.mutable_start();
    start.set_session_id(setup.id);
    *start.mutable_scene() = *std::move(spec);
    start.set_physics_rate_hz(session_options.physics_rate_hz);
    start.set_frame_rate_hz(session_options.frame_rate_hz);
    start.set_created_unix_nanos(absl::ToUnixNanos(absl::Now()));
    start.set_cutter_token_sha256(setup.tokens.cutter_sha256());
    start.set_observer_token_sha256(setup.tokens.observer_sha256());
    if (absl::Status s = (*journal)->Append(record); !s.ok()) return s;
    setup.journal = *std::move(journal);
  }
  const std::string journal_path = setup.journal != nullptr ? setup.journal->path() : std::string();
  absl::StatusOr<std::unique_ptr<Session>> session =
      Session::Create(std::move(setup), session_options);
  if (session.ok()) {
    std::shared_ptr<Session> shared = *std::move(session);
    absl::Status added = Add(shared);  // others may have been made meanwhile
    if (added.ok()) return CreatedSession{std::move(shared), std::move(issued)};
    shared->Close(added, /*for_good=*/true);
    session = added;
  }
  if (!journal_path.empty()) std::remove(journal_path.c_str());  // nothing to keep
  return session.status();
}

absl::StatusOr<CreatedSession> SessionRegistry::CreateReplay(const RecordedSession& recorded,
                                                             SessionOptions options) {
  absl::StatusOr<sim::Scene> scene = sim::BuildScene(recorded.start.scene(), ".");
  if (!scene.ok()) return scene.status();
  options.physics_rate_hz = recorded.start.physics_rate_hz();
  options.frame_rate_hz = recorded.start.frame_rate_hz();
  auto [tokens, issued] = SessionTokens::Generate();
  absl::StatusOr<std::unique_ptr<Session>> session = Session::Create(
      {NewSessionId(), *std::move(scene), std::move(tokens), nullptr, recorded.events, 0}, options);
  if (!session.ok()) return session.status();
  std::shared_ptr<Session> shared = *std::move(session);
  if (absl::Status s = Add(shared); !s.ok()) return s;
  return CreatedSession{std::move(shared), std::move(issued)};
}

std::vector<RestoreOutcome> SessionRegistry::Restore() {
  std::vector<RestoreOutcome> outcomes;
  if (options_.journal_dir.empty()) return outcomes;
  std::error_code error;
  std::vector<std::string> paths;
  for (const auto& entry : std::filesystem::directory_iterator(options_.journal_dir, error)) {
    if (entry.path().extension() == ".journal") paths.push_back(entry.path().string());
  }
  std::sort(paths.begin(), paths.end());
  for (const std::string& path : paths) outcomes.push_back(RestoreOne(path));
  return outcomes;
}

RestoreOutcome SessionRegistry::RestoreOne(const std::string& path) {
  RestoreOutcome outcome;
  outcome.journal = path;
  absl::StatusOr<RecordedSession> recorded = ReadRecordedSession(path);
  if (!recorded.ok()) {
    outcome.status = recorded.status();
    return outcome;
  }
  outcome.warning = recorded->warning;
  outcome.ticks = recorded->last_tick;
  if (recorded->ended) return outcome;  // closed by a client: kept for replay only
  {                                     // before the replay, not after it
    absl::MutexLock lock(&mutex_);
    outcome.status = CheckRoom();
    if (!outcome.status.ok()) return outcome;
  }
  const kerf::v1::JournalStart& start = recorded->start;
  if (start.session_id() + ".journal" != std::filesystem::path(path).filename().string()) {
    outcome.status = absl::InvalidArgumentError(absl::StrCat(
        "journal '", path, "' records session '", start.session_id(), "' under another name"));
    return outcome;
  }
  absl::StatusOr<sim::Scene> scene = sim::BuildScene(start.scene(), ".");
  absl::StatusOr<SessionTokens> tokens =
      SessionTokens::FromDigests(start.cutter_token_sha256(), start.observer_token_sha256());
  if (!scene.ok() || !tokens.ok()) {
    outcome.status = scene.ok() ? tokens.status() : scene.status();
    return outcome;
  }
  // Nothing is changed on disk before everything else is known to be fine.
  if (!recorded->warning.empty()) {
    if (absl::Status s = TruncateJournal(path, recorded->good_bytes); !s.ok()) {
      outcome.status = s;
      return outcome;
    }
  }
  absl::StatusOr<std::unique_ptr<JournalWriter>> journal = JournalWriter::Open(path);
  if (!journal.ok()) {
    outcome.status = journal.status();
    return outcome;
  }
  SessionOptions session_options = options_.session;
  session_options.physics_rate_hz = start.physics_rate_hz();
  session_options.frame_rate_hz = start.frame_rate_hz();
  SessionSetup setup{start.session_id(),  *std::move(scene),           *std::move(tokens),
                     *std::move(journal), std::move(recorded->events), recorded->last_tick};
  absl::StatusOr<std::unique_ptr<Session>> session =
      Session::Create(std::move(setup), session_options);
  if (!session.ok()) {
    outcome.status = session.status();
    return outcome;
  }
  std::shared_ptr<Session> shared = *std::move(session);
  outcome.status = Add(shared);
  if (!outcome.status.ok()) {
    shared->Close(outcome.status);  // not for good: a server with room restores it later
    return outcome;
  }
  outcome.restored = true;
  return outcome;
}

absl::StatusOr<std::shared_ptr<Session>> SessionRegistry::Find(const std::string& id) const {
  absl::MutexLock lock(&mutex_);
  const auto it = sessions_.find(id);
  if (it == sessions_.end()) return absl::NotFoundError(absl::StrCat("no session '", id, "'"));
  return it->second;
}

absl::StatusOr<kerf::v1::SessionInfo> SessionRegistry::Close(const std::string& id) {
  std::shared_ptr<Session> session;
  {
    absl::MutexLock lock(&mutex_);
    const auto it = sessions_.find(id);
    if (it == sessions_.end()) return absl::NotFoundError(absl::StrCat("no session '", id, "'"));
    session = std::move(it->second);
    sessions_.erase(it);
  }
  session->Close(absl::CancelledError(absl::StrCat("session ", id, " was closed")),
                 /*for_good=*/true);
  return session->Info();
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
