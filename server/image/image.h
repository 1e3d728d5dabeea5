#pragma once
// Frames and grids in memory: RGBA, rows top-down (as PNG stores them), 8-bit or 32-bit float.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace shadelab::image {

enum class PixelType { u8, f32 };

struct Image {
  int width = 0, height = 0;
  PixelType type = PixelType::u8;
  std::vector<std::uint8_t> bytes;  // width * height * 4 channels * (1 or 4) bytes

  static Image blank(int width, int height, PixelType type) {
    return {width, height, type, std::vector<std::uint8_t>(static_cast<size_t>(width) * static_cast<size_t>(height) * 4 * (type == PixelType::u8 ? 1 : 4))};
  }
  size_t pixel_bytes() const { return type == PixelType::u8 ? 4 : 16; }
  size_t row_bytes() const { return static_cast<size_t>(width) * pixel_bytes(); }
  std::uint8_t* row(int y) { return bytes.data() + static_cast<size_t>(y) * row_bytes(); }
  const std::uint8_t* row(int y) const { return bytes.data() + static_cast<size_t>(y) * row_bytes(); }
};

}  // namespace shadelab::image
