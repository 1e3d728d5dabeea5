#pragma once
// From GL readback (bottom row first) to what the browser writes into the PNG.
//
// The WebGL canvas is premultiplied (premultipliedAlpha: true), so canvas.toBlob divides colour by
// alpha. The rule, measured on every colour/alpha byte pair in Chromium (docs/homework-contract.md):
//   in float32, c' = c / 255, a' = a / 255, byte = round_half_even(min(1, c' * (1 / a')) * 255);
//   alpha 0 gives (0, 0, 0, 0). Opaque pixels pass unchanged.
#include <cstdint>

#include "image/image.h"

namespace shadelab::image {

// One pixel, in place.
void canvas_blob_pixel(std::uint8_t rgba[4]);

// Flips `bottom_up` (width x height RGBA8) into `out` and applies the toBlob rule.
// Returns true when every pixel is opaque (the PNG can then drop alpha losslessly).
bool canvas_blob_from_readback(const std::uint8_t* bottom_up, Image& out);

// Flips readback of any pixel type (bottom row first) into `out` (top row first), bytes unchanged.
void flip_from_readback(const void* bottom_up, Image& out);

// Flips float readback into `out`; values stay as the drawing buffer holds them (premultiplied,
// NaN and infinity kept), which is what an EXR is for.
void float_from_readback(const float* bottom_up, Image& out);

}  // namespace shadelab::image
