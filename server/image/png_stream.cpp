#include "image/png_stream.h"

#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <string>
#include <thread>

#include "core/cpu_budget.h"

namespace shadelab::image {

namespace {

Error encode_error(const std::string& what) { return make_error(ErrorCode::io_error, "PNG encoding failed: " + what); }

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(v >> shift));
}

void put_chunk(std::vector<std::uint8_t>& out, const char type[4], const std::uint8_t* data, size_t size) {
  put_u32(out, static_cast<std::uint32_t>(size));
  const size_t type_at = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data, data + size);
  const auto crc = crc32_z(0, out.data() + type_at, size + 4);
  put_u32(out, static_cast<std::uint32_t>(crc));
}

// One row as PNG stores it: the filter type byte, then the filtered samples. `above` is the
// previous row's unfiltered samples, or null for the image's first row.
void filter_row(PngFilter filter, const std::uint8_t* row, const std::uint8_t* above, size_t size, int bpp, std::uint8_t* out) {
  out[0] = static_cast<std::uint8_t>(filter);
  std::uint8_t* f = out + 1;
  switch (filter) {
    case PngFilter::none: std::memcpy(f, row, size); break;
    case PngFilter::sub:
      for (size_t i = 0; i < size; ++i) f[i] = static_cast<std::uint8_t>(row[i] - (i >= static_cast<size_t>(bpp) ? row[i - static_cast<size_t>(bpp)] : 0));
      break;
    case PngFilter::up:
      if (above)
        for (size_t i = 0; i < size; ++i) f[i] = static_cast<std::uint8_t>(row[i] - above[i]);
      else
        std::memcpy(f, row, size);
      break;
  }
}

// The RGBA8 row as the PNG's samples: itself, or RGB with alpha dropped.
const std::uint8_t* samples(const Image& image, int y, int channels, std::vector<std::uint8_t>& rgb) {
  const std::uint8_t* rgba = image.row(y);
  if (channels == 4) return rgba;
  rgb.resize(static_cast<size_t>(image.width) * 3);
  for (size_t i = 0, n = static_cast<size_t>(image.width); i < n; ++i) std::memcpy(&rgb[i * 3], &rgba[i * 4], 3);
  return rgb.data();
}

}  // namespace

PngStream::PngStream(int width, int height, int channels, const PngSettings& settings)
    : width_(width), height_(height), channels_(channels), settings_(settings) {
  segments_.reserve(static_cast<size_t>((height + kRowsPerSegment - 1) / kRowsPerSegment));
}

Status PngStream::deflate_segment(const Image& rows, int y_begin, int y_end, Segment& out) const {
  const size_t row_size = static_cast<size_t>(width_) * static_cast<size_t>(channels_);
  std::vector<std::uint8_t> filtered((row_size + 1) * static_cast<size_t>(y_end - y_begin));
  std::vector<std::uint8_t> rgb, rgb_above;
  const std::uint8_t* above = y_begin > 0 ? samples(rows, y_begin - 1, channels_, rgb_above) : nullptr;
  for (int y = y_begin; y < y_end; ++y) {
    const std::uint8_t* row = samples(rows, y, channels_, rgb);
    filter_row(settings_.filter, row, above, row_size, channels_, &filtered[(row_size + 1) * static_cast<size_t>(y - y_begin)]);
    if (channels_ == 3) {
      rgb_above.swap(rgb);
      above = rgb_above.data();
    } else {
      above = row;
    }
  }
  z_stream z{};
  if (deflateInit2(&z, settings_.compression_level, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) return encode_error("zlib would not start");
  out.deflated.resize(deflateBound(&z, filtered.size()) + 16);
  z.next_in = filtered.data();
  z.avail_in = static_cast<uInt>(filtered.size());
  z.next_out = out.deflated.data();
  z.avail_out = static_cast<uInt>(out.deflated.size());
  // The image's last segment ends the stream; every other one ends byte-aligned for the next.
  const int result = deflate(&z, y_end == height_ ? Z_FINISH : Z_SYNC_FLUSH);
  out.deflated.resize(out.deflated.size() - z.avail_out);
  deflateEnd(&z);
  if (result != Z_STREAM_END && result != Z_OK) return encode_error("zlib failed");
  out.adler = static_cast<std::uint32_t>(adler32_z(1, filtered.data(), filtered.size()));
  out.filtered_bytes = filtered.size();
  return Ok{};
}

Status PngStream::write_rows(const Image& rows, int y_begin, int y_end) {
  if (y_begin != rows_received_ || y_end > height_ || y_end <= y_begin || rows.width != width_ || rows.type != PixelType::u8)
    return encode_error("rows out of order");
  rows_received_ = y_end;
  // Whole segments only, counted from row 0: rows past the last whole one wait for the next
  // call (whose image holds them too), so how the rows were handed over never shows in the bytes.
  const int deflate_end = y_end == height_ ? height_ : y_end / kRowsPerSegment * kRowsPerSegment;
  const int from = rows_deflated_;
  const size_t first = segments_.size();
  for (int y = from; y < deflate_end; y += kRowsPerSegment) segments_.emplace_back();
  const size_t count = segments_.size() - first;
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  const auto work = [&] {
    for (size_t i; (i = next++) < count;) {
      const int y = from + static_cast<int>(i) * kRowsPerSegment;
      if (!deflate_segment(rows, y, std::min(y + kRowsPerSegment, deflate_end), segments_[first + i])) failed = true;
    }
  };
  const unsigned cores = settings_.threads > 0 ? static_cast<unsigned>(settings_.threads) : core::usable_cores();
  std::vector<std::jthread> helpers;
  for (unsigned t = 1; t < std::min<size_t>(cores, count); ++t) helpers.emplace_back(work);
  work();
  helpers.clear();  // joins
  if (failed) return encode_error("zlib failed");
  rows_deflated_ = deflate_end;
  return Ok{};
}

Expected<std::vector<std::uint8_t>> PngStream::finish() {
  if (rows_deflated_ != height_) return encode_error("not every row was written");
  std::vector<std::uint8_t> zlib_stream = {0x78, 0x01};  // deflate, 32K window, "fastest" (FCHECK makes it a multiple of 31)
  std::uint32_t adler = 1;
  for (const auto& s : segments_) {
    zlib_stream.insert(zlib_stream.end(), s.deflated.begin(), s.deflated.end());
    adler = static_cast<std::uint32_t>(adler32_combine64(adler, s.adler, static_cast<z_off64_t>(s.filtered_bytes)));
  }
  put_u32(zlib_stream, adler);

  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<std::uint8_t> header;
  put_u32(header, static_cast<std::uint32_t>(width_));
  put_u32(header, static_cast<std::uint32_t>(height_));
  // 8 bits per sample, colour type RGB (2) or RGBA (6), deflate, adaptive filtering, no interlace.
  header.insert(header.end(), {8, static_cast<std::uint8_t>(channels_ == 3 ? 2 : 6), 0, 0, 0});
  png.reserve(zlib_stream.size() + 64);
  put_chunk(png, "IHDR", header.data(), header.size());
  put_chunk(png, "IDAT", zlib_stream.data(), zlib_stream.size());
  put_chunk(png, "IEND", nullptr, 0);
  return png;
}

}  // namespace shadelab::image
