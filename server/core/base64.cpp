#include "core/base64.h"

#include <openssl/evp.h>

#include <algorithm>

namespace shadelab {

namespace {

// EVP_EncodeBlock takes an int length; the input goes through in chunks of a multiple of 3 bytes,
// so the concatenated output is the encoding of the whole.
std::string encode(const unsigned char* data, size_t size) {
  constexpr size_t kChunk = size_t{3} << 24;  // 48 MiB of input, 64 MiB of output a call
  std::string out(4 * ((size + 2) / 3), '\0');
  auto* dst = reinterpret_cast<unsigned char*>(out.data());
  for (size_t done = 0; done < size;) {
    const size_t n = std::min(kChunk, size - done);
    dst += EVP_EncodeBlock(dst, data + done, static_cast<int>(n));
    done += n;
  }
  return out;
}

}  // namespace

std::string base64_encode(std::string_view bytes) { return encode(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()); }

std::string base64_encode(const std::vector<std::uint8_t>& bytes) { return encode(bytes.data(), bytes.size()); }

std::optional<std::string> base64_decode(std::string_view text) {
  constexpr size_t kMax = size_t{1} << 30;  // EVP_DecodeBlock takes an int length
  if (text.size() % 4 != 0 || text.size() > kMax) return std::nullopt;
  std::string out(text.size() / 4 * 3, '\0');
  const int n = EVP_DecodeBlock(reinterpret_cast<unsigned char*>(out.data()), reinterpret_cast<const unsigned char*>(text.data()),
                                static_cast<int>(text.size()));
  if (n < 0) return std::nullopt;
  // EVP_DecodeBlock counts the padding's zero bytes in; the '=' at the end say how many.
  const size_t padding = text.ends_with("==") ? 2 : text.ends_with("=") ? 1 : 0;
  out.resize(static_cast<size_t>(n) - padding);
  return out;
}

}  // namespace shadelab
