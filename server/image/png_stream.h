#pragma once
// A PNG written into memory a band of rows at a time, so encoding can start before the last
// frame of a grid is rendered.
#include <memory>
#include <vector>

#include "core/expected.h"
#include "image/encode.h"
#include "image/image.h"

namespace shadelab::image {

class PngStream {
 public:
  // channels: 3 (drops alpha from the RGBA rows it is given) or 4.
  PngStream(int width, int height, int channels, const PngSettings& settings);
  ~PngStream();
  PngStream(const PngStream&) = delete;
  PngStream& operator=(const PngStream&) = delete;

  int channels() const { return channels_; }
  // Writes rows [y_begin, y_end) of `rows`, an RGBA8 image at least y_end rows tall whose row 0 is
  // the PNG's row 0. Rows must come in order.
  Status write_rows(const Image& rows, int y_begin, int y_end);
  Expected<std::vector<std::uint8_t>> finish();

 private:
  struct State;
  std::unique_ptr<State> state_;
  int width_, height_, channels_;
};

}  // namespace shadelab::image
