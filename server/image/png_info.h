#pragma once
// What a PNG file says about itself before anything decodes it: its signature and its IHDR
// chunk's size, bit depth and colour type. A stranger's PNG (a student's saved frame, a render
// they hand in) is checked here first, so a decoder is never handed a file that claims to be
// 100000 x 100000 pixels.
#include <cstdint>
#include <optional>
#include <string_view>

namespace shadelab::image {

struct PngInfo {
  std::uint32_t width = 0, height = 0;
  int bit_depth = 0;
  int colour_type = 0;  // 0 grey, 2 RGB, 3 palette, 4 grey + alpha, 6 RGBA
};

// The header of `bytes`, or nullopt when they are not a PNG (no signature, no IHDR first).
std::optional<PngInfo> png_info(std::string_view bytes);

}  // namespace shadelab::image
