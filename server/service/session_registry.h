// The sessions a server holds: made from embedded scenes or scene messages, found by id, and
// limited in number. With a journal directory, each session journals itself to
// DIR/<session id>.journal (see session.h and journal_file.h), and a restarting server restores
// every session whose journal was not closed by a client.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/status/statusor.h"
#include "absl/synchronization/mutex.h"
#include "kerf/v1/simulator.pb.h"
#include "service/recorded_session.h"
#include "service/session.h"

namespace kerf::service {

struct RegistryOptions {
  std::size_t max_sessions = 16;
  std::size_t max_scene_tets = 2'000'000;  // largest lattice a client may ask for
  std::string default_scene = "lattice-tension";
  SessionOptions session;   // defaults for rates and limits
  std::string journal_dir;  // empty: sessions are not journaled
};

struct CreatedSession {
  std::shared_ptr<Session> session;
  IssuedTokens tokens;  // handed to the client once, and kept nowhere
};

// What Restore did with one journal.
struct RestoreOutcome {
  std::string journal;  // path
  absl::Status status;  // OK: restored (or closed for good, `restored` false)
  bool restored = false;
  std::string warning;  // a torn or unusable tail that was cut off
  std::uint64_t ticks = 0;
};

class SessionRegistry {
 public:
  explicit SessionRegistry(RegistryOptions options) : options_(std::move(options)) {}

  // NOT_FOUND for an unknown scene name, INVALID_ARGUMENT for a malformed scene, a scene that
  // reads a file (not accepted over the network) or bad rates, RESOURCE_EXHAUSTED at the
  // session limit, INTERNAL when the journal cannot be written.
  absl::StatusOr<CreatedSession> Create(const kerf::v1::CreateSessionRequest& request);
  // Restores the sessions journaled in the journal directory and not closed by a client: each
  // replays its recorded events up to its last one (a torn or unusable tail cut off first, with
  // a warning) and then runs on, appending to the same journal. A journal that cannot be
  // restored is reported and left as it is. Call before serving.
  std::vector<RestoreOutcome> Restore();
  // A new session (new id and tokens, no journal) replaying `recorded` at its ticks, to be
  // watched; `options` gives the speed and limits (the rates are the recording's).
  // INVALID_ARGUMENT for a recording whose scene does not build, RESOURCE_EXHAUSTED at the
  // session limit.
  absl::StatusOr<CreatedSession> CreateReplay(const RecordedSession& recorded,
                                              SessionOptions options);
  // NOT_FOUND naming the id.
  absl::StatusOr<std::shared_ptr<Session>> Find(const std::string& id) const;
  // Closes the session for good (its journal records the end and is kept for replay); its
  // final state and counts. NOT_FOUND naming the id.
  absl::StatusOr<kerf::v1::SessionInfo> Close(const std::string& id);
  // Ends every session's streams with `why` (for a graceful shutdown).
  void CloseAll(const absl::Status& why);
  std::vector<std::shared_ptr<Session>> List() const;

 private:
  RestoreOutcome RestoreOne(const std::string& path);
  // RESOURCE_EXHAUSTED at the session limit.
  absl::Status CheckRoom() const ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  // Adds `session` unless the limit is reached meanwhile.
  absl::Status Add(std::shared_ptr<Session> session);

  const RegistryOptions options_;
  mutable absl::Mutex mutex_;
  absl::flat_hash_map<std::string, std::shared_ptr<Session>> sessions_ ABSL_GUARDED_BY(mutex_);
};

}  // namespace kerf::service
