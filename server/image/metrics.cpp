#include "image/metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/check.h"

namespace shadelab::image {

namespace {

int channel_diff(const std::uint8_t* a, const std::uint8_t* b) {
  return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
}

// CompareOptions::outline_tolerance: whether `a` is a blend the expected neighbourhood of (x, y)
// allows, where that neighbourhood holds the clear background.
bool blend_on_outline(const std::uint8_t* a, const Image& expected, int x, int y, int limit) {
  int lo[3] = {255, 255, 255}, hi[3] = {0, 0, 0};
  bool background = false;
  for (int ny = std::max(0, y - 1); ny <= std::min(expected.height - 1, y + 1); ++ny)
    for (int nx = std::max(0, x - 1); nx <= std::min(expected.width - 1, x + 1); ++nx) {
      const std::uint8_t* e = expected.bytes.data() + (static_cast<std::size_t>(ny) * expected.width + nx) * 4;
      background |= e[0] == 0 && e[1] == 0 && e[2] == 0;
      for (int c = 0; c < 3; ++c) lo[c] = std::min<int>(lo[c], e[c]), hi[c] = std::max<int>(hi[c], e[c]);
    }
  if (!background) return false;
  for (int c = 0; c < 3; ++c)
    if (a[c] < lo[c] - limit || a[c] > hi[c] + limit) return false;
  return true;
}

// Mean SSIM of luma over 7 x 7 windows. Luma stays an integer (Rec. 601 in thousandths: 299 R +
// 587 G + 114 B), so each window's sums are exact in 64 bits, kept as running sums: a row's column
// sums move down a row at a time and a window's sums right a column at a time, O(pixels).
double mean_ssim(const Image& a, const Image& b) {
  const int w = a.width, h = a.height, r = 3, side = 2 * r + 1;
  if (w < side || h < side) return 1.0;
  const auto luma = [&](const Image& img) {
    std::vector<std::int64_t> y(static_cast<std::size_t>(w) * h);
    for (std::size_t i = 0; i < y.size(); ++i) {
      const std::uint8_t* p = img.bytes.data() + i * 4;
      y[i] = 299 * p[0] + 587 * p[1] + 114 * p[2];
    }
    return y;
  };
  const std::vector<std::int64_t> la = luma(a), lb = luma(b);
  struct Sums {
    std::int64_t x = 0, y = 0, xx = 0, yy = 0, xy = 0;
    void add(std::int64_t va, std::int64_t vb, std::int64_t sign) {
      x += sign * va, y += sign * vb, xx += sign * va * va, yy += sign * vb * vb, xy += sign * va * vb;
    }
    void add(const Sums& o, std::int64_t sign) { x += sign * o.x, y += sign * o.y, xx += sign * o.xx, yy += sign * o.yy, xy += sign * o.xy; }
  };
  std::vector<Sums> column(static_cast<std::size_t>(w));  // over rows [top, top + side) of each column
  const auto add_row = [&](int row, std::int64_t sign) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(row) * w + x;
      column[static_cast<std::size_t>(x)].add(la[i], lb[i], sign);
    }
  };
  for (int row = 0; row < side; ++row) add_row(row, 1);
  constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03, scale = 255.0 * 1000.0;
  const double n = side * side, to_mean = 1.0 / (n * scale), to_square = 1.0 / (n * scale * scale);
  double total = 0;
  for (int top = 0;; ++top) {
    Sums window;
    for (int x = 0; x < side; ++x) window.add(column[static_cast<std::size_t>(x)], 1);
    for (int left = 0;; ++left) {
      const double ma = static_cast<double>(window.x) * to_mean, mb = static_cast<double>(window.y) * to_mean;
      const double va = std::max(0.0, static_cast<double>(window.xx) * to_square - ma * ma);
      const double vb = std::max(0.0, static_cast<double>(window.yy) * to_square - mb * mb);
      const double cov = static_cast<double>(window.xy) * to_square - ma * mb;
      total += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
      if (left + side == w) break;
      window.add(column[static_cast<std::size_t>(left + side)], 1);
      window.add(column[static_cast<std::size_t>(left)], -1);
    }
    if (top + side == h) break;
    add_row(top + side, 1);
    add_row(top, -1);
  }
  return total / (static_cast<double>(w - side + 1) * (h - side + 1));
}

// Whether the pixel at (x, y), already known to differ by more than `limit`, still fails after
// the spatial and outline allowances.
bool fails_after_allowances(const std::uint8_t* a, const Image& expected, int x, int y, int limit, const CompareOptions& options) {
  const int w = expected.width, h = expected.height;
  for (int dy = -1; dy <= 1 && options.spatial_tolerance; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = x + dx, ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
      if (channel_diff(a, expected.bytes.data() + (static_cast<std::size_t>(ny) * w + nx) * 4) <= limit) return false;
    }
  return !(options.outline_tolerance && blend_on_outline(a, expected, x, y, limit));
}

int threshold_limit(const CompareOptions& options) { return static_cast<int>(std::floor(options.threshold * 255.0 + 1e-9)); }

void check_comparable(const Image& actual, const Image& expected) {
  SHADELAB_CHECK(actual.type == PixelType::u8 && expected.type == PixelType::u8, "compare takes RGBA8");
  SHADELAB_CHECK(actual.width == expected.width && actual.height == expected.height, "compare needs equal sizes");
}

}  // namespace

std::size_t failing_pixels(const Image& actual, const Image& expected, const CompareOptions& options) {
  check_comparable(actual, expected);
  if (actual.bytes == expected.bytes) return 0;
  const int w = actual.width, h = actual.height, limit = threshold_limit(options);
  std::size_t failing = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * w + x) * 4;
      const std::uint8_t* a = actual.bytes.data() + i;
      if (channel_diff(a, expected.bytes.data() + i) > limit && fails_after_allowances(a, expected, x, y, limit, options)) ++failing;
    }
  return failing;
}

FrameMetrics compare(const Image& actual, const Image& expected, const CompareOptions& options) {
  check_comparable(actual, expected);
  FrameMetrics m;
  m.identical = actual.bytes == expected.bytes;
  const int w = actual.width, h = actual.height;
  const int limit = threshold_limit(options);
  double sum_sq = 0;
  int worst = 0;
  std::size_t failing = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * w + x) * 4;
      const std::uint8_t* a = actual.bytes.data() + i;
      const std::uint8_t* e = expected.bytes.data() + i;
      for (int c = 0; c < 3; ++c) sum_sq += (a[c] - e[c]) * (a[c] - e[c]) / (255.0 * 255.0);
      const int d = channel_diff(a, e);
      worst = std::max(worst, d);
      if (d > limit && fails_after_allowances(a, expected, x, y, limit, options)) ++failing;
    }
  const double pixels = static_cast<double>(w) * h;
  m.rmse = std::sqrt(sum_sq / (pixels * 3));
  if (!m.identical) m.psnr = m.rmse > 0 ? 20.0 * std::log10(1.0 / m.rmse) : 200.0;  // differing only in alpha
  m.max_abs = worst / 255.0;
  m.failing_fraction = static_cast<double>(failing) / pixels;
  m.ssim = m.identical ? 1.0 : mean_ssim(actual, expected);
  return m;
}

NonFinite count_non_finite(const Image& f) {
  SHADELAB_CHECK(f.type == PixelType::f32, "count_non_finite takes a float frame");
  NonFinite out;
  const std::size_t pixels = static_cast<std::size_t>(f.width) * f.height;
  for (std::size_t i = 0; i < pixels; ++i) {
    float px[4];
    std::memcpy(px, f.bytes.data() + i * 16, sizeof px);
    bool nan = false, inf = false;
    for (float v : px) nan |= std::isnan(v), inf |= std::isinf(v);
    out.nan += nan;
    out.inf += inf && !nan;
  }
  return out;
}

NonFinite count_census(const std::uint8_t* rgba, std::size_t pixels, bool second) {
  NonFinite out;
  const std::uint8_t* flags = rgba + (second ? 2 : 0);
  for (std::size_t i = 0; i < pixels; ++i, flags += 4) {
    const bool nan = flags[0] != 0;
    out.nan += nan;
    out.inf += !nan && flags[1] != 0;
  }
  return out;
}

Image difference_blocks(const Image& actual, const Image& expected, int side, const CompareOptions& options) {
  check_comparable(actual, expected);
  SHADELAB_CHECK(side > 0, "a block has a side");
  const int w = actual.width, h = actual.height, limit = threshold_limit(options);
  Image out = Image::blank(w, h, PixelType::u8);
  for (int by = 0; by < h; by += side)
    for (int bx = 0; bx < w; bx += side) {
      const int x1 = std::min(w, bx + side), y1 = std::min(h, by + side);
      std::size_t failing = 0;
      for (int y = by; y < y1; ++y)
        for (int x = bx; x < x1; ++x) {
          const std::uint8_t* a = actual.bytes.data() + (static_cast<std::size_t>(y) * w + x) * 4;
          failing += channel_diff(a, expected.bytes.data() + (static_cast<std::size_t>(y) * w + x) * 4) > limit &&
                     fails_after_allowances(a, expected, x, y, limit, options);
        }
      const std::size_t pixels = static_cast<std::size_t>(x1 - bx) * static_cast<std::size_t>(y1 - by);
      const std::array<std::uint8_t, 3> shade = failing == 0 ? std::array<std::uint8_t, 3>{0, 0, 0}
                                                : 2 * failing > pixels ? std::array<std::uint8_t, 3>{255, 255, 0}
                                                                       : std::array<std::uint8_t, 3>{255, 0, 0};
      for (int y = by; y < y1; ++y)
        for (int x = bx; x < x1; ++x) {
          std::uint8_t* o = out.bytes.data() + (static_cast<std::size_t>(y) * w + x) * 4;
          o[0] = shade[0], o[1] = shade[1], o[2] = shade[2], o[3] = 255;
        }
    }
  return out;
}

Image heatmap(const Image& actual, const Image& expected) {
  Image out = Image::blank(actual.width, actual.height, PixelType::u8);
  for (std::size_t i = 0; i < out.bytes.size(); i += 4) {
    const double d = channel_diff(actual.bytes.data() + i, expected.bytes.data() + i) / 255.0;
    const double t = std::min(1.0, d * 2.0);  // 0.5 difference saturates
    out.bytes[i] = static_cast<std::uint8_t>(std::min(255.0, t * 3 * 255));
    out.bytes[i + 1] = static_cast<std::uint8_t>(std::clamp((t * 3 - 1) * 255, 0.0, 255.0));
    out.bytes[i + 2] = static_cast<std::uint8_t>(std::clamp((t * 3 - 2) * 255, 0.0, 255.0));
    out.bytes[i + 3] = 255;
  }
  return out;
}

}  // namespace shadelab::image
