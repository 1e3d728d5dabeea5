#pragma once
// Encodes the grid PNG while frames are still being rendered: a background thread writes each
// band of cells (one grid row) as soon as its frames have arrived, so the encode overlaps the
// rendering of later frames and the job ends shortly after the last frame.
//
// Whether the PNG can be RGB (every pixel opaque) is decided from the first band, since the file's
// channel count must be known before its first row; if a later frame has transparent pixels the
// grid is re-encoded as RGBA at the end. Shaders that write alpha < 1 nearly always do so from
// frame 0, so the re-encode is rare, and it is only slower, never wrong.
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#include "core/expected.h"
#include "image/encode.h"
#include "image/grid.h"

namespace shadelab::image {

class GridPngEncoder {
 public:
  GridPngEncoder(const GridLayout& layout, int frame_count, const PngSettings& settings = {});
  ~GridPngEncoder();  // abandons an unfinished encode
  GridPngEncoder(const GridPngEncoder&) = delete;
  GridPngEncoder& operator=(const GridPngEncoder&) = delete;

  // Thread-safe; frames may arrive in any order. `opaque`: every alpha byte is 255.
  void add_frame(int index, const Image& frame, bool opaque);
  // Waits for the encode of all frames.
  Expected<std::vector<std::uint8_t>> finish();
  bool reencoded() const { return reencoded_; }  // for tests and metrics

 private:
  void run();
  bool band_ready(int band) const;
  bool band_opaque(int band) const;

  GridLayout layout_;
  int frame_count_;
  PngSettings settings_;
  Image grid_;
  std::vector<char> ready_, opaque_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  bool abandoned_ = false;
  bool reencoded_ = false;
  Expected<std::vector<std::uint8_t>> result_{Error{ErrorCode::io_error, "encode not finished", {}, {}}};
  std::thread worker_;
};

}  // namespace shadelab::image
