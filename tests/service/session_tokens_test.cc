// SessionTokens: the digests a session keeps of the tokens it issues, and how it checks them.
#include "service/session_tokens.h"

#include <gtest/gtest.h>

#include "absl/strings/escaping.h"
#include "service/sha256.h"

namespace kerf::service {
namespace {

TEST(SessionTokens, KeepsOnlyTheDigestsOfTheTokensItIssues) {
  EXPECT_EQ(absl::BytesToHexString(Sha256("abc")),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");  // FIPS 180-2
  const auto [tokens, issued] = SessionTokens::Generate();
  EXPECT_EQ(issued.cutter.size(), 64u);
  EXPECT_NE(issued.cutter, issued.observer);
  EXPECT_EQ(tokens.cutter_sha256(), Sha256(issued.cutter));
  EXPECT_EQ(tokens.observer_sha256(), Sha256(issued.observer));
  // Rebuilt from the digests alone (as a restored session is), it admits the same tokens.
  const absl::StatusOr<SessionTokens> kept =
      SessionTokens::FromDigests(tokens.cutter_sha256(), tokens.observer_sha256());
  ASSERT_TRUE(kept.ok()) << kept.status();
  EXPECT_TRUE(kept->Authorize(Role::kCutter, issued.cutter).ok());
  EXPECT_TRUE(kept->Authorize(Role::kObserver, issued.observer).ok());
  EXPECT_EQ(kept->Authorize(Role::kCutter, issued.observer).code(),
            absl::StatusCode::kPermissionDenied);
  // The digest itself is no token.
  EXPECT_EQ(kept->Authorize(Role::kObserver, tokens.cutter_sha256()).code(),
            absl::StatusCode::kPermissionDenied);
  EXPECT_EQ(kept->Authorize(Role::kObserver, "").code(), absl::StatusCode::kUnauthenticated);
  EXPECT_EQ(SessionTokens::FromDigests("short", tokens.observer_sha256()).status().code(),
            absl::StatusCode::kInvalidArgument);
}

TEST(SessionTokens, ComparesWholeTokens) {
  EXPECT_TRUE(ConstantTimeEquals("abc", "abc"));
  EXPECT_FALSE(ConstantTimeEquals("abc", "abd"));
  EXPECT_FALSE(ConstantTimeEquals("abc", "ab"));
  EXPECT_FALSE(ConstantTimeEquals("", "a"));
}

}  // namespace
}  // namespace kerf::service
