#include "sheet/cairo_png.h"
#include "sheet/narrowed_png.h"

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

std::string narrowed_png(const std::string& png, int max_width) {
  Surface image = decode_png(png);
  if (!image) return png;
  const int w = cairo_image_surface_get_width(image.get()), h = cairo_image_surface_get_height(image.get());
  if (w <= max_width || max_width <= 0) return png;
  const double scale = static_cast<double>(max_width) / w;
  Surface out(cairo_image_surface_create(cairo_image_surface_get_format(image.get()), max_width,
                                         std::max(1, static_cast<int>(h * scale + 0.5))),
              cairo_surface_destroy);
  cairo_t* cr = cairo_create(out.get());
  cairo_scale(cr, scale, scale);
  cairo_set_source_surface(cr, image.get(), 0, 0);
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_GOOD);  // averages what a step drops, at any scale
  cairo_paint(cr);
  cairo_destroy(cr);
  std::string bytes = encode_png(out.get());
  return bytes.empty() ? png : bytes;
}

}  // namespace shadelab::sheet
