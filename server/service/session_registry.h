// The sessions a server holds: made from embedded scenes or scene messages, found by id, and
// limited in number.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/status/statusor.h"
#include "absl/synchronization/mutex.h"
#include "kerf/v1/simulator.pb.h"
#include "service/session.h"

namespace kerf::service {

struct RegistryOptions {
  std::size_t max_sessions = 16;
  std::size_t max_scene_tets = 2'000'000;  // largest lattice a client may ask for
  std::string default_scene = "lattice-tension";
  SessionOptions session;  // defaults for rates and limits
};

class SessionRegistry {
 public:
  explicit SessionRegistry(RegistryOptions options) : options_(std::move(options)) {}

  // NOT_FOUND for an unknown scene name, INVALID_ARGUMENT for a malformed scene, a scene that
  // reads a file (not accepted over the network) or bad rates, RESOURCE_EXHAUSTED at the
  // session limit.
  absl::StatusOr<std::shared_ptr<Session>> Create(const kerf::v1::CreateSessionRequest& request);
  // NOT_FOUND naming the id.
  absl::StatusOr<std::shared_ptr<Session>> Find(const std::string& id) const;
  absl::Status Close(const std::string& id);
  // Ends every session's streams with `why` (for a graceful shutdown).
  void CloseAll(const absl::Status& why);
  std::vector<std::shared_ptr<Session>> List() const;

 private:
  const RegistryOptions options_;
  mutable absl::Mutex mutex_;
  absl::flat_hash_map<std::string, std::shared_ptr<Session>> sessions_ ABSL_GUARDED_BY(mutex_);
};

}  // namespace kerf::service
