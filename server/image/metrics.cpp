#include "image/metrics.h"

#include <algorithm>
#include <cmath>
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

// Mean SSIM of luma over 7 x 7 windows, from summed-area tables (O(pixels)).
double mean_ssim(const Image& a, const Image& b) {
  const int w = a.width, h = a.height, r = 3;
  if (w < 2 * r + 1 || h < 2 * r + 1) return 1.0;
  const auto luma = [](const Image& img, std::size_t i) {
    const std::uint8_t* p = img.bytes.data() + i * 4;
    return (0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]) / 255.0;
  };
  const std::size_t stride = static_cast<std::size_t>(w) + 1;
  std::vector<double> sx(stride * (h + 1)), sy(sx.size()), sxx(sx.size()), syy(sx.size()), sxy(sx.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      const double va = luma(a, i), vb = luma(b, i);
      const std::size_t s = (y + 1) * stride + (x + 1), up = y * stride + (x + 1), left = (y + 1) * stride + x, diag = y * stride + x;
      sx[s] = va + sx[up] + sx[left] - sx[diag];
      sy[s] = vb + sy[up] + sy[left] - sy[diag];
      sxx[s] = va * va + sxx[up] + sxx[left] - sxx[diag];
      syy[s] = vb * vb + syy[up] + syy[left] - syy[diag];
      sxy[s] = va * vb + sxy[up] + sxy[left] - sxy[diag];
    }
  const auto box = [&](const std::vector<double>& t, int x0, int y0, int x1, int y1) {
    return t[y1 * stride + x1] - t[y0 * stride + x1] - t[y1 * stride + x0] + t[y0 * stride + x0];
  };
  constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  const double n = (2 * r + 1) * (2 * r + 1);
  double total = 0;
  std::size_t windows = 0;
  for (int y = r; y < h - r; ++y)
    for (int x = r; x < w - r; ++x) {
      const int x0 = x - r, y0 = y - r, x1 = x + r + 1, y1 = y + r + 1;
      const double ma = box(sx, x0, y0, x1, y1) / n, mb = box(sy, x0, y0, x1, y1) / n;
      const double va = std::max(0.0, box(sxx, x0, y0, x1, y1) / n - ma * ma);
      const double vb = std::max(0.0, box(syy, x0, y0, x1, y1) / n - mb * mb);
      const double cov = box(sxy, x0, y0, x1, y1) / n - ma * mb;
      total += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
      ++windows;
    }
  return total / static_cast<double>(windows);
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
