// The two secrets of a session: the cutter token (cut, observe, close) and the observer token
// (observe, snapshot). Random (256 bits from the kernel), handed out once when the session is
// made, and never logged, listed or stored: the session keeps only their SHA-256 digests (so a
// journal on disk does not hold them), and a token presented is hashed and compared in constant
// time.
#pragma once

#include <string>
#include <utility>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace kerf::service {

enum class Role { kCutter, kObserver };

// The tokens themselves, for the client that made the session (64 hex digits each).
struct IssuedTokens {
  std::string cutter;
  std::string observer;
};

class SessionTokens {
 public:
  // Two fresh random tokens, and the digests that check them.
  static std::pair<SessionTokens, IssuedTokens> Generate();
  // From digests kept earlier (32 bytes each); INVALID_ARGUMENT otherwise.
  static absl::StatusOr<SessionTokens> FromDigests(std::string cutter_sha256,
                                                   std::string observer_sha256);

  // OK when `token` grants `role`; UNAUTHENTICATED for no token, PERMISSION_DENIED for a wrong
  // one or the observer token where the cutter's is needed. Messages never echo a token.
  absl::Status Authorize(Role role, absl::string_view token) const;

  const std::string& cutter_sha256() const { return cutter_sha256_; }
  const std::string& observer_sha256() const { return observer_sha256_; }

 private:
  SessionTokens(std::string cutter_sha256, std::string observer_sha256)
      : cutter_sha256_(std::move(cutter_sha256)), observer_sha256_(std::move(observer_sha256)) {}
  std::string cutter_sha256_, observer_sha256_;  // 32 raw bytes each
};

// Equality whose time depends only on the lengths, not on where the strings differ.
bool ConstantTimeEquals(absl::string_view a, absl::string_view b);

}  // namespace kerf::service
