#include "mesh/io/base64.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace kerf::mesh::internal {
namespace {

using ::testing::ElementsAre;

TEST(Base64, KnownVectorsFromRfc4648) {
  EXPECT_EQ(Base64Encode(""), "");
  EXPECT_EQ(Base64Encode("f"), "Zg==");
  EXPECT_EQ(Base64Encode("fo"), "Zm8=");
  EXPECT_EQ(Base64Encode("foo"), "Zm9v");
  EXPECT_EQ(Base64Encode("foobar"), "Zm9vYmFy");
  EXPECT_THAT(*Base64Decode("Zm9vYg=="), ElementsAre('f', 'o', 'o', 'b'));
}

TEST(Base64, DecodesConcatenatedPaddedBlocksAndSkipsWhitespace) {
  EXPECT_THAT(*Base64Decode("Zg==\n Zm8="), ElementsAre('f', 'f', 'o'));
}

TEST(Base64, RefusesBadInput) {
  EXPECT_FALSE(Base64Decode("Zm9").has_value());   // truncated group
  EXPECT_FALSE(Base64Decode("Z===").has_value());  // too much padding
  EXPECT_FALSE(Base64Decode("Zm=v").has_value());  // data after padding
  EXPECT_FALSE(Base64Decode("Zm9*").has_value());  // not in the alphabet
}

TEST(Base64, RoundTripsAllByteValues) {
  std::string bytes;
  for (int i = 0; i < 256; ++i) bytes += static_cast<char>(i);
  const auto decoded = Base64Decode(Base64Encode(bytes));
  ASSERT_TRUE(decoded.has_value());
  EXPECT_EQ(std::string(decoded->begin(), decoded->end()), bytes);
}

}  // namespace
}  // namespace kerf::mesh::internal
