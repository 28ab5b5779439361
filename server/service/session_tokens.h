// The two secrets of a session: the cutter token (cut, observe, close) and the observer token
// (observe, snapshot). Random (256 bits from the kernel), compared in constant time, and never
// logged or listed.
#pragma once

#include <string>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"

namespace kerf::service {

enum class Role { kCutter, kObserver };

class SessionTokens {
 public:
  // Two fresh random tokens (64 hex digits each).
  static SessionTokens Generate();

  // OK when `token` grants `role`; UNAUTHENTICATED for no token, PERMISSION_DENIED for a wrong
  // one or the observer token where the cutter's is needed. Messages never echo a token.
  absl::Status Authorize(Role role, absl::string_view token) const;

  const std::string& cutter() const { return cutter_; }
  const std::string& observer() const { return observer_; }

 private:
  SessionTokens(std::string cutter, std::string observer)
      : cutter_(std::move(cutter)), observer_(std::move(observer)) {}
  std::string cutter_, observer_;
};

// Equality whose time depends only on the lengths, not on where the strings differ.
bool ConstantTimeEquals(absl::string_view a, absl::string_view b);

}  // namespace kerf::service
