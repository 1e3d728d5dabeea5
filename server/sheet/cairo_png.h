#pragma once
// PNG bytes in and out of cairo image surfaces, in memory: what the PDF layout and the
// saved-frames grid share. Owners are unique_ptrs that destroy the surface.
#include <cairo.h>

#include <memory>
#include <string>

namespace shadelab::sheet {

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

// The decoded image, or a null surface when cairo cannot read it. Check the header first
// (image/png_info.h) for anything a stranger sent.
Surface decode_png(const std::string& bytes);
// The surface as PNG bytes; empty when cairo fails.
std::string encode_png(cairo_surface_t* surface);

// cairo's write callback into a std::string (also the PDF stream's).
cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length);

}  // namespace shadelab::sheet
