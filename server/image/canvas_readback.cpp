#include "image/canvas_readback.h"

#include <array>
#include <cmath>
#include <cstring>

namespace shadelab::image {

namespace {
// The rule for every (colour, alpha) byte pair, computed once: 64 KiB.
const std::array<std::uint8_t, 256 * 256>& unpremultiply_table() {
  static const auto table = [] {
    std::array<std::uint8_t, 256 * 256> t{};
    for (int a = 1; a < 256; ++a) {
      const float inv = 1.0f / (static_cast<float>(a) / 255.0f);
      for (int c = 0; c < 256; ++c) {
        const float v = std::fmin(1.0f, (static_cast<float>(c) / 255.0f) * inv) * 255.0f;
        t[static_cast<size_t>(a) * 256 + static_cast<size_t>(c)] = static_cast<std::uint8_t>(std::nearbyint(v));
      }
    }
    return t;
  }();
  return table;
}
}  // namespace

void canvas_blob_pixel(std::uint8_t px[4]) {
  const std::uint8_t a = px[3];
  if (a == 255) return;
  if (a == 0) {
    px[0] = px[1] = px[2] = 0;
    return;
  }
  const auto& t = unpremultiply_table();
  const size_t row = static_cast<size_t>(a) * 256;
  for (int i = 0; i < 3; ++i) px[i] = t[row + px[i]];
}

bool canvas_blob_from_readback(const std::uint8_t* bottom_up, Image& out) {
  const size_t row_bytes = out.row_bytes();
  bool opaque = true;
  for (int y = 0; y < out.height; ++y) {
    std::uint8_t* dst = out.row(out.height - 1 - y);
    std::memcpy(dst, bottom_up + static_cast<size_t>(y) * row_bytes, row_bytes);
    for (size_t x = 3; x < row_bytes; x += 4) {
      if (dst[x] != 255) {
        opaque = false;
        canvas_blob_pixel(dst + x - 3);
      }
    }
  }
  return opaque;
}

void flip_from_readback(const void* bottom_up, Image& out) {
  const size_t row_bytes = out.row_bytes();
  const auto* src = static_cast<const std::uint8_t*>(bottom_up);
  for (int y = 0; y < out.height; ++y) std::memcpy(out.row(out.height - 1 - y), src + static_cast<size_t>(y) * row_bytes, row_bytes);
}

void float_from_readback(const float* bottom_up, Image& out) { flip_from_readback(bottom_up, out); }

}  // namespace shadelab::image
