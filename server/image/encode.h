#pragma once
// Encoding images into memory (no temporary files): PNG with ShadeLab's own writer (the hot
// path), EXR with OpenEXR (OpenImageIO's EXR writer is OpenEXR too, behind 267 libraries that
// every process paid ~250 ms to load; OpenImageIO reads the outputs back in the tests).
#include <cstdint>
#include <vector>

#include "core/expected.h"
#include "image/image.h"

namespace shadelab::image {

// The PNG row filters (PNG 1.2, section 6): each row is stored as its difference from its left
// neighbour (sub), from the row above (up), or as it is (none).
enum class PngFilter : std::uint8_t { none = 0, sub = 1, up = 2 };

// OpenImageIO's PNG writer with its defaults (zlib level 6, adaptive filters) took ~160 ms for the
// 1920 x 1440 grid; level 1 with the UP filter and RGB when opaque ~31 ms for ~10% more bytes;
// ShadeLab's own writer (image/png_stream.h) with the same settings on several threads less
// again. docs/performance-log.md has the measurements.
struct PngSettings {
  int compression_level = 1;
  PngFilter filter = PngFilter::up;  // fastest and smallest single filter on these images
  int threads = 0;                   // deflate threads; 0: one per core
};

// RGBA8 image -> PNG bytes. Opaque images are written as RGB (lossless: every alpha is 255).
Expected<std::vector<std::uint8_t>> encode_png(const Image& image, const PngSettings& settings = {});
// RGBA float image -> OpenEXR (half-float would lose the exact values graders compare: float).
Expected<std::vector<std::uint8_t>> encode_exr(const Image& image);

bool is_opaque(const Image& image);

}  // namespace shadelab::image
