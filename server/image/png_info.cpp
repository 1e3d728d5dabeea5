#include "image/png_info.h"

#include <cstring>

namespace shadelab::image {

namespace {
std::uint32_t big_endian(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | std::uint32_t{p[3]};
}
}  // namespace

std::optional<PngInfo> png_info(std::string_view bytes) {
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  // Signature, then the IHDR chunk: length 13, type, width, height, depth, colour type, ...
  if (bytes.size() < 8 + 8 + 13 || std::memcmp(bytes.data(), kSignature, 8) != 0) return std::nullopt;
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data()) + 8;
  if (big_endian(p) != 13 || std::memcmp(p + 4, "IHDR", 4) != 0) return std::nullopt;
  PngInfo info{big_endian(p + 8), big_endian(p + 12), p[16], p[17]};
  if (info.width == 0 || info.height == 0) return std::nullopt;
  return info;
}

}  // namespace shadelab::image
