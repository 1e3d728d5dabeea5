#include "model/surface.h"

#include <algorithm>
#include <cstring>

namespace shadelab::model {

namespace {

struct Texel {
  float r, g, b, a;
};

Texel texel(const image::Image& image, std::size_t index) {
  Texel t{};
  std::memcpy(&t, image.bytes.data() + index * sizeof(Texel), sizeof(Texel));
  return t;
}

}  // namespace

FrameSurface surface_from(const image::Image& position) {
  FrameSurface s;
  s.width = position.width;
  s.height = position.height;
  const std::size_t count = static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.height);
  for (std::size_t i = 0; i < count; ++i) {
    const Texel p = texel(position, i);
    // The clear colour's alpha is 1 and the position render writes 2: the resolve's alpha is 1 +
    // the share of samples the mesh covers.
    if (p.a <= 1) continue;
    if (p.a < 2) {  // some samples see the background
      s.outline.push_back(static_cast<std::uint32_t>(i));
      continue;
    }
    s.pixels.push_back(static_cast<std::uint32_t>(i));
    s.points.push_back({{p.r, p.g, p.b}, {}, {}});
  }
  return s;
}

namespace {

glm::vec3& quantity_of(SurfacePoint& p, Quantity q) {
  switch (q) {
    case Quantity::sample_flat_normal: break;  // kept apart from the points: add_sample
    case Quantity::position: return p.position;
    case Quantity::normal: return p.normal;
    case Quantity::flat_normal: return p.flat_normal;
    case Quantity::colour: return p.colour;
    case Quantity::flat_colour: return p.flat_colour;
  }
  return p.position;
}

}  // namespace

namespace {

void add_sample(FrameSurface& s, const image::Image& render, int sample) {
  if (sample < 0 || sample >= kMaxSamples) return;
  if (s.sample_flat_normals.empty()) s.sample_flat_normals.resize(s.points.size() * kMaxSamples);
  for (std::size_t i = 0; i < s.pixels.size(); ++i) {
    const Texel t = texel(render, s.pixels[i]);
    // A sample of an interior pixel the shifted render leaves uncovered (the rasteriser's rounding
    // of a silhouette's edge): the pixel's averaged flat normal stands for it.
    s.sample_flat_normals[i * kMaxSamples + static_cast<std::size_t>(sample)] = t.a > 1 ? glm::vec3{t.r, t.g, t.b} : s.points[i].flat_normal;
  }
  s.samples = std::max(s.samples, sample + 1);
}

}  // namespace

void add_quantity(FrameSurface& s, const image::Image& render, Quantity quantity, int sample) {
  if (quantity == Quantity::sample_flat_normal) return add_sample(s, render, sample);
  for (std::size_t i = 0; i < s.pixels.size(); ++i) {
    const Texel t = texel(render, s.pixels[i]);
    quantity_of(s.points[i], quantity) = {t.r, t.g, t.b};
  }
}

}  // namespace shadelab::model
