#include "grade/difference_regions.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/common.hpp>

#include "core/words.h"

namespace shadelab::grade {

namespace {

enum Region { highlight, lit, unlit, sideways, up_or_down, facing, outline, kRegions };
constexpr const char* kRegionNames[] = {"the highlight",
                                        "the lit side",
                                        "the unlit side",
                                        "the parts facing sideways (mostly red)",
                                        "the parts facing up or down (mostly green)",
                                        "the parts facing the viewer or away (mostly blue)",
                                        "the outline"};

// A highlight pixel: the course's specular term there is at least a quarter of its peak.
constexpr float kHighlight = 0.25f;
// A part with fewer of its pixels off is not named: a correct submission may differ that much.
constexpr double kNoticeable = 0.01;

// The normal's colour is by the normal's largest component: the parts the homework's notebook asks
// about ("why are the surfaces that face the viewer blue?").
Region axis_of(const glm::vec3& n) {
  const glm::vec3 a = glm::abs(n);
  if (a.x >= a.y && a.x >= a.z) return sideways;
  return a.y >= a.z ? up_or_down : facing;
}

Region region_of(const model::SurfacePoint& p, const model::Light& light, const model::FitOptions& o) {
  if (o.terms == model::Terms::normal_colour) return axis_of(p.normal);
  const model::Factors f = model::factors(model::Variant::formula, p, light);
  if (o.terms == model::Terms::phong && model::specular_factor(f, o.course.exponent) >= kHighlight) return highlight;
  return f.d > 0 ? lit : unlit;
}

struct Tally {
  std::size_t pixels = 0, off = 0;
  double sum[3] = {0, 0, 0};
};

void count_pixel(Tally& t, const image::Image& student, const image::Image& reference, std::uint32_t pixel, double threshold) {
  ++t.pixels;
  const std::uint8_t* s = student.bytes.data() + static_cast<std::size_t>(pixel) * 4;
  const std::uint8_t* r = reference.bytes.data() + static_cast<std::size_t>(pixel) * 4;
  double d[3];
  for (int c = 0; c < 3; ++c) d[c] = (static_cast<double>(s[c]) - r[c]) / 255.0;
  if (std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])}) <= threshold) return;
  ++t.off;
  for (int c = 0; c < 3; ++c) t.sum[c] += d[c];
}

std::string signed_number(double v) {
  char out[16];
  std::snprintf(out, sizeof out, "%+.2f", v);
  return out;
}

}  // namespace

std::vector<RegionDifference> difference_regions(const std::vector<model::FrameSurface>& surfaces, const SharedFrames& student,
                                                 const SharedFrames& reference, const model::Light& light, const model::FitOptions& o) {
  Tally tally[kRegions];
  for (std::size_t k = 0; k < surfaces.size() && k < student.size() && k < reference.size(); ++k) {
    const auto& s = surfaces[k];
    for (std::size_t i = 0; i < s.points.size(); ++i) count_pixel(tally[region_of(s.points[i], light, o)], *student[k], *reference[k], s.pixels[i], o.threshold);
    for (const std::uint32_t pixel : s.outline) count_pixel(tally[outline], *student[k], *reference[k], pixel, o.threshold);
  }
  std::vector<RegionDifference> out;
  for (int r = 0; r < kRegions; ++r) {
    const Tally& t = tally[r];
    if (t.pixels == 0 || static_cast<double>(t.off) < kNoticeable * static_cast<double>(t.pixels)) continue;
    RegionDifference d{kRegionNames[r], static_cast<double>(t.off) / static_cast<double>(t.pixels)};
    for (int c = 0; c < 3; ++c) d.mean[c] = t.sum[c] / static_cast<double>(t.off);
    out.push_back(d);
  }
  return out;
}

std::string to_words(const RegionDifference& d) {
  const bool brighter = d.mean[0] >= 0 && d.mean[1] >= 0 && d.mean[2] >= 0;
  const bool darker = d.mean[0] <= 0 && d.mean[1] <= 0 && d.mean[2] <= 0;
  const std::string how = brighter ? "brighter" : darker ? "darker" : "another hue";
  return d.region + ": " + percent(d.share) + " of its pixels, " + how + " (red " + signed_number(d.mean[0]) + ", green " +
         signed_number(d.mean[1]) + ", blue " + signed_number(d.mean[2]) + ")";
}

}  // namespace shadelab::grade
