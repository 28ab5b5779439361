#include "service/session_tokens.h"

#include <sys/random.h>

#include <array>
#include <cassert>
#include <cstdint>

#include "absl/strings/escaping.h"

namespace kerf::service {
namespace {

std::string RandomToken() {
  std::array<char, 32> bytes;
  std::size_t filled = 0;
  while (filled < bytes.size()) {  // getrandom may return fewer bytes (or EINTR): go on
    const ssize_t n = getrandom(bytes.data() + filled, bytes.size() - filled, 0);
    if (n > 0) filled += static_cast<std::size_t>(n);
  }
  return absl::BytesToHexString(absl::string_view(bytes.data(), bytes.size()));
}

}  // namespace

SessionTokens SessionTokens::Generate() {
  SessionTokens tokens(RandomToken(), RandomToken());
  assert(tokens.cutter_ != tokens.observer_);
  return tokens;
}

bool ConstantTimeEquals(absl::string_view a, absl::string_view b) {
  if (a.size() != b.size()) return false;
  // Every byte is looked at; the accumulator is volatile so that the loop is not cut short.
  volatile std::uint8_t difference = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    difference = difference | static_cast<std::uint8_t>(a[i] ^ b[i]);
  }
  return difference == 0;
}

absl::Status SessionTokens::Authorize(Role role, absl::string_view token) const {
  if (token.empty()) {
    return absl::UnauthenticatedError(
        "a session token is needed: the cutter or observer token that CreateSession returned");
  }
  // Both comparisons always run, so that the time does not tell which token it was near.
  const bool is_cutter = ConstantTimeEquals(token, cutter_);
  const bool is_observer = ConstantTimeEquals(token, observer_);
  if (is_cutter) return absl::OkStatus();
  if (is_observer && role == Role::kObserver) return absl::OkStatus();
  if (is_observer) return absl::PermissionDeniedError("the observer token cannot cut or close");
  return absl::PermissionDeniedError("the token does not belong to this session");
}

}  // namespace kerf::service
