#include "service/session_tokens.h"

#include <sys/random.h>

#include <array>
#include <cstdint>

#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"
#include "base/check.h"
#include "service/sha256.h"

namespace kerf::service {
namespace {

constexpr std::size_t kDigestBytes = 32;

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

std::pair<SessionTokens, IssuedTokens> SessionTokens::Generate() {
  IssuedTokens issued{RandomToken(), RandomToken()};
  KERF_CHECK(issued.cutter != issued.observer);
  return {SessionTokens(Sha256(issued.cutter), Sha256(issued.observer)), std::move(issued)};
}

absl::StatusOr<SessionTokens> SessionTokens::FromDigests(std::string cutter_sha256,
                                                         std::string observer_sha256) {
  if (cutter_sha256.size() != kDigestBytes || observer_sha256.size() != kDigestBytes) {
    return absl::InvalidArgumentError(absl::StrCat("token digests must be ", kDigestBytes,
                                                   " bytes, got ", cutter_sha256.size(), " and ",
                                                   observer_sha256.size()));
  }
  return SessionTokens(std::move(cutter_sha256), std::move(observer_sha256));
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
  const std::string digest = Sha256(token);
  const bool is_cutter = ConstantTimeEquals(digest, cutter_sha256_);
  const bool is_observer = ConstantTimeEquals(digest, observer_sha256_);
  if (is_cutter) return absl::OkStatus();
  if (is_observer && role == Role::kObserver) return absl::OkStatus();
  if (is_observer) return absl::PermissionDeniedError("the observer token cannot cut or close");
  return absl::PermissionDeniedError("the token does not belong to this session");
}

}  // namespace kerf::service
