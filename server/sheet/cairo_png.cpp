#include "sheet/cairo_png.h"

#include <algorithm>

namespace shadelab::sheet {

namespace {
struct PngReader {
  const std::string& bytes;
  size_t at = 0;
};
cairo_status_t read_png(void* closure, unsigned char* data, unsigned int length) {
  auto& r = *static_cast<PngReader*>(closure);
  if (r.bytes.size() - r.at < length) return CAIRO_STATUS_READ_ERROR;
  std::copy_n(r.bytes.data() + r.at, length, data);
  r.at += length;
  return CAIRO_STATUS_SUCCESS;
}
}  // namespace

cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

Surface decode_png(const std::string& bytes) {
  PngReader reader{bytes};
  Surface img(cairo_image_surface_create_from_png_stream(read_png, &reader), cairo_surface_destroy);
  if (cairo_surface_status(img.get()) != CAIRO_STATUS_SUCCESS) return Surface(nullptr, cairo_surface_destroy);
  return img;
}

std::string encode_png(cairo_surface_t* surface) {
  std::string out;
  if (cairo_surface_write_to_png_stream(surface, append_to_string, &out) != CAIRO_STATUS_SUCCESS) return {};
  return out;
}

}  // namespace shadelab::sheet
