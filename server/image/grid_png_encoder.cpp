#include "image/grid_png_encoder.h"

#include <optional>

#include "image/png_stream.h"

namespace shadelab::image {

GridPngEncoder::GridPngEncoder(const GridLayout& layout, int frame_count, const PngSettings& settings)
    : layout_(layout),
      frame_count_(frame_count),
      settings_(settings),
      grid_(Image::blank(layout.width(), layout.height(), PixelType::u8)),
      ready_(static_cast<size_t>(layout.cells()), 0),
      opaque_(static_cast<size_t>(layout.cells()), 0) {
  // Cells with no frame are finished from the start: transparent black.
  for (int i = frame_count; i < layout.cells(); ++i) ready_[static_cast<size_t>(i)] = 1;
  worker_ = std::thread([this] { run(); });
}

GridPngEncoder::~GridPngEncoder() {
  {
    std::lock_guard lock(mutex_);
    abandoned_ = true;
  }
  changed_.notify_all();
  if (worker_.joinable()) worker_.join();
}

void GridPngEncoder::add_frame(int index, const Image& frame, bool opaque) {
  // Cells do not overlap, so copying outside the lock is safe; the flag publishes it.
  place_frame(layout_, index, frame, grid_);
  {
    std::lock_guard lock(mutex_);
    ready_[static_cast<size_t>(index)] = 1;
    opaque_[static_cast<size_t>(index)] = opaque ? 1 : 0;
  }
  changed_.notify_all();
}

bool GridPngEncoder::band_ready(int band) const {
  for (int c = 0; c < layout_.columns; ++c)
    if (!ready_[static_cast<size_t>(band * layout_.columns + c)]) return false;
  return true;
}

bool GridPngEncoder::band_opaque(int band) const {
  for (int c = 0; c < layout_.columns; ++c) {
    const int i = band * layout_.columns + c;
    if (i >= frame_count_ || !opaque_[static_cast<size_t>(i)]) return false;
  }
  return true;
}

void GridPngEncoder::run() {
  std::optional<PngStream> png;
  bool must_reencode = false;
  for (int band = 0; band < layout_.rows && !must_reencode; ++band) {
    bool opaque = false;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return abandoned_ || band_ready(band); });
      if (abandoned_) return;
      opaque = band_opaque(band);
    }
    if (!png) png.emplace(layout_.width(), layout_.height(), opaque ? 3 : 4, settings_);
    if (png->channels() == 3 && !opaque) {
      must_reencode = true;
      break;
    }
    if (auto s = png->write_rows(grid_, band * layout_.cell_height, (band + 1) * layout_.cell_height); !s) {
      std::lock_guard lock(mutex_);
      result_ = s.take_error();
      return;
    }
  }
  if (must_reencode) {
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] {
        if (abandoned_) return true;
        for (int b = 0; b < layout_.rows; ++b)
          if (!band_ready(b)) return false;
        return true;
      });
      if (abandoned_) return;
    }
    reencoded_ = true;
    png.emplace(layout_.width(), layout_.height(), 4, settings_);
    if (auto s = png->write_rows(grid_, 0, layout_.height()); !s) {
      std::lock_guard lock(mutex_);
      result_ = s.take_error();
      return;
    }
  }
  auto bytes = png->finish();
  std::lock_guard lock(mutex_);
  result_ = std::move(bytes);
}

Expected<std::vector<std::uint8_t>> GridPngEncoder::finish() {
  {
    std::lock_guard lock(mutex_);
    for (int b = 0; b < layout_.rows; ++b)
      if (!band_ready(b)) abandoned_ = true;  // a frame never came: the caller's render failed
  }
  changed_.notify_all();
  if (worker_.joinable()) worker_.join();
  if (abandoned_) return make_error(ErrorCode::io_error, "the grid is missing frames");
  return std::move(result_);
}

}  // namespace shadelab::image
