#include "sheet/saved_grid.h"

#include <algorithm>

#include "image/png_info.h"
#include "sheet/cairo_png.h"

namespace shadelab::sheet {

Expected<std::string> saved_frames_grid(const std::vector<std::pair<std::string, std::string>>& named_pngs, int columns, int cell_width) {
  if (named_pngs.empty()) return make_error(ErrorCode::invalid_argument, "no saved frames");
  std::vector<Surface> frames;
  for (const auto& [name, bytes] : named_pngs) {
    const auto info = image::png_info(bytes);
    if (!info) return make_error(ErrorCode::invalid_argument, name + " is not a PNG file");
    if (info->width > kMaxSavedFrameSide || info->height > kMaxSavedFrameSide)
      return make_error(ErrorCode::invalid_argument, name + " is " + std::to_string(info->width) + " x " + std::to_string(info->height) +
                                                         " pixels: larger than a frame of the page (at most " +
                                                         std::to_string(kMaxSavedFrameSide) + " a side)");
    Surface decoded = decode_png(bytes);
    if (!decoded) return make_error(ErrorCode::invalid_argument, name + " cannot be read as a PNG file");
    frames.push_back(std::move(decoded));
  }
  const int first_w = cairo_image_surface_get_width(frames[0].get()), first_h = cairo_image_surface_get_height(frames[0].get());
  const int w = cell_width > 0 ? cell_width : first_w;
  const int h = cell_width > 0 ? std::max(1, static_cast<int>(static_cast<long>(first_h) * cell_width / first_w)) : first_h;
  const int count = static_cast<int>(frames.size()), rows = (count + columns - 1) / columns;
  Surface grid(cairo_image_surface_create(CAIRO_FORMAT_RGB24, std::min(count, columns) * w, rows * h), cairo_surface_destroy);
  cairo_t* cr = cairo_create(grid.get());
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  for (int k = 0; k < count; ++k) {
    cairo_surface_t* f = frames[static_cast<size_t>(k)].get();
    cairo_save(cr);
    cairo_translate(cr, (k % columns) * w, (k / columns) * h);
    cairo_scale(cr, static_cast<double>(w) / cairo_image_surface_get_width(f), static_cast<double>(h) / cairo_image_surface_get_height(f));
    cairo_set_source_surface(cr, f, 0, 0);
    cairo_paint(cr);
    cairo_restore(cr);
  }
  cairo_destroy(cr);
  std::string png = encode_png(grid.get());
  if (png.empty()) return make_error(ErrorCode::io_error, "cairo could not write the saved frames' grid");
  return png;
}

}  // namespace shadelab::sheet
