#include "pipeline/report/base64.h"

#include <string>

#include <gtest/gtest.h>

namespace sfm {
namespace {

// RFC 4648 section 10.
TEST(Base64Test, Rfc4648Vectors) {
  const std::pair<std::string, std::string> vectors[] = {
      {"", ""},         {"f", "Zg=="},         {"fo", "Zm8="},         {"foo", "Zm9v"},
      {"foob", "Zm9vYg=="}, {"fooba", "Zm9vYmE="}, {"foobar", "Zm9vYmFy"}};
  for (const auto& [plain, encoded] : vectors) {
    EXPECT_EQ(Base64Encode(plain), encoded) << plain;
    std::string decoded;
    ASSERT_TRUE(Base64Decode(encoded, &decoded)) << encoded;
    EXPECT_EQ(decoded, plain);
  }
}

TEST(Base64Test, EveryByteValueRoundTrips) {
  std::string bytes;
  for (int i = 0; i < 256; ++i) bytes += static_cast<char>(i);
  const std::string encoded = Base64Encode(bytes);
  EXPECT_EQ(encoded.substr(0, 8), "AAECAwQF");   // 00 01 02 03 04 05
  EXPECT_EQ(encoded.substr(encoded.size() - 4), "/w==");  // ff, padded
  std::string decoded;
  ASSERT_TRUE(Base64Decode(encoded, &decoded));
  EXPECT_EQ(decoded, bytes);
}

TEST(Base64Test, RejectsMalformedText) {
  std::string decoded;
  EXPECT_FALSE(Base64Decode("Zm9", &decoded));       // length not a multiple of 4
  EXPECT_FALSE(Base64Decode("Zm9v!A==", &decoded));  // outside the alphabet
  EXPECT_FALSE(Base64Decode("Zg==Zm9v", &decoded));  // padding before the end
  EXPECT_FALSE(Base64Decode("Z===", &decoded));      // three pad characters
  EXPECT_FALSE(Base64Decode("Zm=v", &decoded));      // pad inside a group
}

}  // namespace
}  // namespace sfm
