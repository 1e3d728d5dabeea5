// core/base64.h: RFC 4648's test vectors, and inputs longer than one call of OpenSSL's encoder.
#include "core/base64.h"

#include <gtest/gtest.h>

namespace shadelab {
namespace {

TEST(Base64Test, EncodesRfc4648Vectors) {
  EXPECT_EQ(base64_encode(std::string_view("")), "");
  EXPECT_EQ(base64_encode(std::string_view("f")), "Zg==");
  EXPECT_EQ(base64_encode(std::string_view("fo")), "Zm8=");
  EXPECT_EQ(base64_encode(std::string_view("foo")), "Zm9v");
  EXPECT_EQ(base64_encode(std::string_view("foob")), "Zm9vYg==");
  EXPECT_EQ(base64_encode(std::string_view("fooba")), "Zm9vYmE=");
  EXPECT_EQ(base64_encode(std::string_view("foobar")), "Zm9vYmFy");
}

TEST(Base64Test, EncodesEveryByteValueAndNoLineBreaks) {
  std::vector<std::uint8_t> bytes;
  for (int i = 0; i < 256; ++i) bytes.push_back(static_cast<std::uint8_t>(i));
  const std::string text = base64_encode(bytes);
  EXPECT_EQ(text.size(), 344u);
  EXPECT_EQ(text.find('\n'), std::string::npos);
  EXPECT_EQ(text.substr(0, 8), "AAECAwQF");
  EXPECT_EQ(text.substr(336), "/P3+/w==");
}

// The encoder takes its input in chunks of 48 MiB (OpenSSL counts in int): the chunks' encodings
// must join into the encoding of the whole, with padding only at the very end.
TEST(Base64Test, ALongInputEncodesAsItsChunksJoined) {
  constexpr size_t kChunk = size_t{3} << 24;
  std::vector<std::uint8_t> bytes(kChunk + 2);
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(i * 7 + i / 251);
  const std::string whole = base64_encode(bytes);
  const std::vector<std::uint8_t> head(bytes.begin(), bytes.begin() + kChunk), tail(bytes.begin() + kChunk, bytes.end());
  EXPECT_EQ(whole.size(), 4 * ((bytes.size() + 2) / 3));
  EXPECT_TRUE(whole == base64_encode(head) + base64_encode(tail));
  EXPECT_EQ(whole.back(), '=');
}

// What a client sends a PNG as: the bytes back, whatever their padding; anything else refused.
TEST(Base64Test, DecodingGivesTheBytesBackAndRefusesWhatIsNotBase64) {
  for (const std::string& bytes : {std::string(), std::string("a"), std::string("ab"), std::string("abc"), std::string("\x89PNG\r\n\x1a\n\0\0", 10)})
    EXPECT_EQ(base64_decode(base64_encode(bytes)), bytes) << bytes.size();
  EXPECT_FALSE(base64_decode("abc"));
  EXPECT_FALSE(base64_decode("ab!="));
  EXPECT_FALSE(base64_decode("ab\ncd=="));
}

}  // namespace
}  // namespace shadelab
