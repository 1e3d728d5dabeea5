#pragma once
// Where an MSAA pixel's samples lie: the standard pattern Direct3D and Vulkan fix and Mesa's
// llvmpipe and most GPUs use (gallium's u_default_get_sample_position), in GL's window
// coordinates within the pixel ((0, 0) its lower-left corner). The renderer's tests check it
// against the driver's own resolve.
#include <array>
#include <span>

namespace shadelab::render {

// The positions of `samples` samples per pixel: 2 or 4; empty for a count without a pattern here.
std::span<const std::array<double, 2>> standard_sample_positions(int samples);

}  // namespace shadelab::render
