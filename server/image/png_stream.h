#pragma once
// A PNG written into memory a band of rows at a time, so encoding can start before the last
// frame of a grid is rendered, and deflated on several threads at once.
//
// The image data is one zlib stream made of independent segments of kRowsPerSegment rows, counted
// from row 0: each deflated on its own (no back-references into the one before) and ended on a
// byte boundary with a sync flush, the Adler-32s combined; the construction pigz uses. The
// segments follow from the image's height alone, never from the thread count or from how the
// rows were handed over, so a 2-core and a 16-core machine, the overlapped grid encoder and a
// one-call encode all write the same bytes.
#include <cstdint>
#include <vector>

#include "core/expected.h"
#include "image/encode.h"
#include "image/image.h"

namespace shadelab::image {

class PngStream {
 public:
  static constexpr int kRowsPerSegment = 32;

  // channels: 3 (drops alpha from the RGBA rows it is given) or 4.
  PngStream(int width, int height, int channels, const PngSettings& settings);

  int channels() const { return channels_; }
  // Writes rows [y_begin, y_end) of `rows`, an RGBA8 image at least y_end rows tall whose row 0 is
  // the PNG's row 0 (the row above y_begin is read too: the UP filter refers to it). Rows must
  // come in order.
  Status write_rows(const Image& rows, int y_begin, int y_end);
  Expected<std::vector<std::uint8_t>> finish();

 private:
  struct Segment {
    std::vector<std::uint8_t> deflated;
    std::uint32_t adler = 1;
    std::uint64_t filtered_bytes = 0;
  };
  Status deflate_segment(const Image& rows, int y_begin, int y_end, Segment& out) const;

  int width_, height_, channels_;
  PngSettings settings_;
  int rows_received_ = 0;  // rows handed over so far
  int rows_deflated_ = 0;  // rows in segments_: whole segments, or all of them
  std::vector<Segment> segments_;
};

}  // namespace shadelab::image
