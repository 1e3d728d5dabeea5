#pragma once
// Comparing a frame with its reference, as a grader needs it. Values are in [0, 1] per channel
// over RGB (alpha is compared through the toBlob result the pixels already hold).
#include <cstddef>
#include <optional>

#include "image/image.h"

namespace shadelab::image {

struct CompareOptions {
  // A pixel fails when some channel differs by more than this. Blender's render tests use 0.016.
  double threshold = 0.016;
  // Accept a pixel that matches some reference pixel within one pixel of it: edge rasterisation
  // differs between GPUs and drivers, and a student should not fail for it.
  bool spatial_tolerance = false;
  // Accept a pixel on the object's outline (the expected frame's clear black within one pixel)
  // whose channels each lie within what the expected 3 x 3 neighbourhood spans, give or take the
  // threshold: an outline pixel is its coverage's blend of object and background, and rasterisers
  // that snap vertices differently (SwiftShader to 1/16 pixel, llvmpipe and GPUs to 1/256) cover
  // it differently. For frames from another rasteriser (a student's saved frames).
  bool outline_tolerance = false;
};

struct FrameMetrics {
  bool identical = false;
  double rmse = 0;
  std::optional<double> psnr;  // dB; none when identical (infinite)
  double ssim = 1;             // mean SSIM of luma, 7 x 7 windows
  double max_abs = 0;
  double failing_fraction = 0; // share of pixels over the threshold
};

// Both RGBA8, the same size.
FrameMetrics compare(const Image& actual, const Image& expected, const CompareOptions& options = {});

// How many pixels compare() counts as failing, without the rest of its work (SSIM's summed-area
// tables are most of it): what a grader comparing against many candidates needs.
std::size_t failing_pixels(const Image& actual, const Image& expected, const CompareOptions& options = {});

// NaN and infinite pixels of a float frame (any channel; a pixel with both counts as NaN).
struct NonFinite {
  std::size_t nan = 0, inf = 0;
};
NonFinite count_non_finite(const Image& float_frame);

// The same counts from a census the grader's program drew (shader/uniform_variants.h): `pixels`
// RGBA8 pixels, one run's flags in (R, G) or, with `second`, (B, A); a flag is any nonzero byte.
NonFinite count_census(const std::uint8_t* rgba, std::size_t pixels, bool second);

// Per-pixel maximum channel difference as a heat map: black, red, yellow, white at 1/8, 1/4, 1/2.
Image heatmap(const Image& actual, const Image& expected);

// Where two frames differ, by square blocks of `side` pixels (the last row and column cut by the
// frame's edge), each in one of three shades of the same ramp: black where no pixel fails
// (the grader's own test: `options`' threshold and allowances), red where some do, yellow where
// more than half do. A picture a student cannot invert to the reference's pixels
// (grade::DifferencePicture::blocks).
Image difference_blocks(const Image& actual, const Image& expected, int side, const CompareOptions& options = {});

}  // namespace shadelab::image
