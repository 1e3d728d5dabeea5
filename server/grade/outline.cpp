#include "grade/outline.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace shadelab::grade {

namespace {

struct Rgba {
  double r = 0, g = 0, b = 0, a = 0;
};

Rgba pixel(const image::Image& im, int x, int y) {
  const std::uint8_t* p = im.row(y) + static_cast<size_t>(x) * 4;
  return {p[0] / 255.0, p[1] / 255.0, p[2] / 255.0, p[3] / 255.0};
}

// The border's commonest colour: border pixels binned at 4 bits a channel, the fullest bin's mean.
Rgba background_of(const image::Image& im) {
  std::map<std::array<int, 4>, std::pair<Rgba, int>> bins;
  const auto add = [&](int x, int y) {
    const std::uint8_t* p = im.row(y) + static_cast<size_t>(x) * 4;
    auto& [sum, n] = bins[{p[0] >> 4, p[1] >> 4, p[2] >> 4, p[3] >> 4}];
    const Rgba c = pixel(im, x, y);
    sum = {sum.r + c.r, sum.g + c.g, sum.b + c.b, sum.a + c.a};
    ++n;
  };
  for (int x = 0; x < im.width; ++x) add(x, 0), add(x, im.height - 1);
  for (int y = 1; y + 1 < im.height; ++y) add(0, y), add(im.width - 1, y);
  const auto fullest = std::max_element(bins.begin(), bins.end(), [](const auto& a, const auto& b) { return a.second.second < b.second.second; });
  const auto& [sum, n] = fullest->second;
  return {sum.r / n, sum.g / n, sum.b / n, sum.a / n};
}

}  // namespace

double Outline::coverage() const {
  if (inside.empty()) return 0;
  return static_cast<double>(std::count(inside.begin(), inside.end(), 1)) / static_cast<double>(inside.size());
}

bool Outline::touches_border() const {
  for (int x = 0; x < width; ++x)
    if (inside[static_cast<size_t>(x)] || inside[static_cast<size_t>(height - 1) * width + x]) return true;
  for (int y = 0; y < height; ++y)
    if (inside[static_cast<size_t>(y) * width] || inside[static_cast<size_t>(y) * width + width - 1]) return true;
  return false;
}

Outline outline_of(const image::Image& im, double tolerance) {
  Outline out{im.width, im.height, std::vector<std::uint8_t>(static_cast<size_t>(im.width) * im.height, 1)};
  if (im.width == 0 || im.height == 0 || im.type != image::PixelType::u8) return out;
  const Rgba bg = background_of(im);
  // A transparent film's colour is whatever the writer left there: only its alpha counts.
  const bool transparent = bg.a < 0.5;
  const auto background_like = [&](int x, int y) {
    const Rgba c = pixel(im, x, y);
    if (transparent) return c.a < 0.5;
    return c.a >= 0.5 && std::max({std::abs(c.r - bg.r), std::abs(c.g - bg.g), std::abs(c.b - bg.b)}) <= tolerance;
  };
  // Flood the background in from the border, four-connected.
  std::vector<std::pair<int, int>> stack;
  const auto reach = [&](int x, int y) {
    std::uint8_t& cell = out.inside[static_cast<size_t>(y) * im.width + x];
    if (cell && background_like(x, y)) cell = 0, stack.emplace_back(x, y);
  };
  for (int x = 0; x < im.width; ++x) reach(x, 0), reach(x, im.height - 1);
  for (int y = 0; y < im.height; ++y) reach(0, y), reach(im.width - 1, y);
  while (!stack.empty()) {
    const auto [x, y] = stack.back();
    stack.pop_back();
    if (x > 0) reach(x - 1, y);
    if (x + 1 < im.width) reach(x + 1, y);
    if (y > 0) reach(x, y - 1);
    if (y + 1 < im.height) reach(x, y + 1);
  }
  return out;
}

Outline resampled(const Outline& o, int width, int height) {
  Outline out{width, height, std::vector<std::uint8_t>(static_cast<size_t>(width) * height, 0)};
  if (o.width == 0 || o.height == 0) return out;
  const double sx = static_cast<double>(o.width) / width, sy = static_cast<double>(o.height) / height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      // The source pixels whose centres fall in this cell; at least the nearest one.
      const int x0 = static_cast<int>(std::floor(x * sx)), x1 = std::max(x0 + 1, static_cast<int>(std::floor((x + 1) * sx)));
      const int y0 = static_cast<int>(std::floor(y * sy)), y1 = std::max(y0 + 1, static_cast<int>(std::floor((y + 1) * sy)));
      size_t in = 0, all = 0;
      for (int v = y0; v < std::min(y1, o.height); ++v)
        for (int u = x0; u < std::min(x1, o.width); ++u) in += o.inside[static_cast<size_t>(v) * o.width + u], ++all;
      out.inside[static_cast<size_t>(y) * width + x] = all > 0 && 2 * in > all;
    }
  return out;
}

double overlap(const Outline& a, const Outline& b) {
  size_t both = 0, either = 0;
  for (size_t i = 0; i < std::min(a.inside.size(), b.inside.size()); ++i) {
    both += a.inside[i] && b.inside[i];
    either += a.inside[i] || b.inside[i];
  }
  return either == 0 ? 1.0 : static_cast<double>(both) / static_cast<double>(either);
}

OutlinePlace place_of(const Outline& o) {
  double sx = 0, sy = 0, n = 0;
  int left = o.width, top = o.height, right = -1, bottom = -1;
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x)
      if (o.inside[static_cast<size_t>(y) * o.width + x]) {
        sx += x + 0.5, sy += y + 0.5, n += 1;
        left = std::min(left, x), right = std::max(right, x), top = std::min(top, y), bottom = std::max(bottom, y);
      }
  if (n == 0) return {};
  const double w = o.width, h = o.height;
  return {sx / n / w, sy / n / h, left / w, top / h, (right + 1) / w, (bottom + 1) / h};
}

}  // namespace shadelab::grade
