#pragma once
// An image narrowed to be looked at in a page that limits its size (a PrairieLearn result), drawn
// by cairo (sheet/cairo_png.cpp) without its header reaching the caller.
#include <string>

namespace shadelab::sheet {

// The PNG no wider than `max_width` (scaled down in its shape, each pixel an average of what it
// covers: an image to look at, not to measure); the bytes unchanged when already that narrow or
// not readable.
std::string narrowed_png(const std::string& png, int max_width);

}  // namespace shadelab::sheet
