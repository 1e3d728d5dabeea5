#include "model/fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>

#include <glm/common.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "model/least_squares.h"
#include "model/simplex.h"

namespace shadelab::model {

namespace {

// A variant whose sample is off on more than this many times the share the frames allow is off on
// some frame (4,096 pixels: the share's standard error is a fifth of a percent).
constexpr double kSampleMargin = 1.5;

glm::vec3 drawn_colour(const image::Image& image, std::uint32_t pixel) {
  const std::uint8_t* p = image.bytes.data() + static_cast<std::size_t>(pixel) * 4;
  return glm::vec3(p[0], p[1], p[2]) / 255.0f;
}

// Every frame's interior pixels at an even stride, `count` in all at most: the same pixels on
// every run.
std::vector<Sampled> sample_of(const std::vector<DrawnFrame>& frames, std::size_t count) {
  std::size_t total = 0;
  for (const auto& f : frames) total += f.surface->points.size();
  const std::size_t stride = std::max<std::size_t>(1, total / std::max<std::size_t>(count, 1));
  std::vector<Sampled> out;
  std::size_t at = 0;
  for (std::size_t k = 0; k < frames.size(); ++k)
    for (std::size_t i = 0; i < frames[k].surface->points.size(); ++i, ++at)
      if (at % stride == 0) out.push_back({k, i, drawn_colour(*frames[k].drawn, frames[k].surface->pixels[i])});
  return out;
}

// The light's alpha is taken as 1, as the page sets it.
float alpha_of(const Factors& f, const Parameters& p, Terms terms) {
  if (terms == Terms::normal_colour) return 1;
  float a = p.colours.alpha[0] + p.colours.alpha[1] * f.d;
  if (terms == Terms::phong) a += p.colours.alpha[2] * specular_factor(f, p.exponent);
  return a;
}

glm::vec4 shaded(const Factors& f, const Parameters& p, Terms terms) {
  if (terms == Terms::normal_colour) return {f.colour, 1};
  glm::vec3 c = p.colours.ambient + f.diffuse_light * p.colours.diffuse * f.d;
  if (terms == Terms::phong) c += f.specular_light * p.colours.specular * specular_factor(f, p.exponent);
  return {c, alpha_of(f, p, terms)};
}

}  // namespace

glm::vec3 as_canvas_stores(const glm::vec4& c) {
  const glm::vec4 bytes = glm::round(glm::clamp(c, 0.0f, 1.0f) * 255.0f);
  if (bytes.a >= 255) return glm::vec3(bytes) / 255.0f;
  if (bytes.a <= 0) return glm::vec3(0);
  return glm::round(glm::min(glm::vec3(1), glm::vec3(bytes) / bytes.a) * 255.0f) / 255.0f;
}

namespace {

double rms_of(const std::vector<Sampled>& sample, const std::vector<Factors>& f, const Parameters& p, Terms terms) {
  double sum = 0;
  for (std::size_t i = 0; i < sample.size(); ++i) {
    const glm::vec3 d = as_canvas_stores(shaded(f[i], p, terms)) - sample[i].drawn;
    sum += static_cast<double>(glm::dot(d, d)) / 3;
  }
  return sample.empty() ? 0 : std::sqrt(sum / static_cast<double>(sample.size()));
}

// The course's colours, at the exponent that draws the sample closest with them. A fit's colours
// drift with its exponent (a highlight a little dimmer and a little narrower draws nearly the same
// pixels, and the 8 bits cannot tell them apart), so where only the exponent changed, the fitted
// colours may land just past the tolerance on one machine's frames and within it on another's: a
// colour the frames do not need changed is not a change to tell (FormulaStabilityTest).
Trial course_colours(const std::vector<Sampled>& sample, const std::vector<Factors>& f, const FitOptions& o) {
  return best_exponent(
      [&](float alpha) {
        Parameters p = o.course;
        p.exponent = alpha;
        return Trial{p, rms_of(sample, f, p, o.terms)};
      },
      o);
}

// Whether the model draws a pixel off. Where its alpha is under 1 the canvas divides the colour by
// it, and so an error of a colour step by as much: the threshold is the colour's before the division.
bool off(const glm::vec4& model, const glm::vec3& drawn, double threshold) {
  const glm::vec3 d = glm::abs(as_canvas_stores(model) - drawn);
  const double alpha = std::clamp(static_cast<double>(model.a), 1.0 / 255, 1.0);
  return std::max({d.r, d.g, d.b}) > threshold / alpha;
}

// The share of the sample drawn off: a variant far off here is not checked on every pixel.
double sample_failing(const std::vector<Sampled>& sample, const std::vector<Factors>& f, const Parameters& p, const FitOptions& o) {
  std::size_t failing = 0;
  for (std::size_t i = 0; i < sample.size(); ++i) failing += off(shaded(f[i], p, o.terms), sample[i].drawn, o.threshold);
  return sample.empty() ? 1 : static_cast<double>(failing) / static_cast<double>(sample.size());
}

}  // namespace

glm::vec4 shade(Variant variant, const Parameters& parameters, Terms terms, const SurfacePoint& point, const Light& light,
                std::span<const glm::vec3> samples) {
  return shaded(factors(variant, point, {parameters.light_position.value_or(light.position), light.colour}, samples), parameters, terms);
}

namespace {

// Whether some interior pixel within one of `pixel` has the model's colour close to `drawn`.
// `model` holds the model's colour at every interior pixel (alpha < 0 elsewhere).
bool near_neighbour(const std::vector<glm::vec4>& model, int width, int height, std::uint32_t pixel, const glm::vec3& drawn, double threshold) {
  const int x = static_cast<int>(pixel % static_cast<std::uint32_t>(width)), y = static_cast<int>(pixel / static_cast<std::uint32_t>(width));
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = x + dx, ny = y + dy;
      if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
      const glm::vec4& m = model[static_cast<std::size_t>(ny) * static_cast<std::size_t>(width) + static_cast<std::size_t>(nx)];
      if (m.a >= 0 && !off(m, drawn, threshold)) return true;
    }
  return false;
}

}  // namespace

double failing_share(Variant v, const Parameters& p, const DrawnFrame& frame, const FitOptions& o) {
  const auto& s = *frame.surface;
  if (s.points.empty()) return 0;
  std::size_t failing = 0;
  if (!o.spatial_tolerance) {
    for (std::size_t i = 0; i < s.points.size(); ++i)
      failing += off(shade(v, p, o.terms, s.points[i], frame.light, s.samples_of(i)), drawn_colour(*frame.drawn, s.pixels[i]), o.threshold);
  } else {
    std::vector<glm::vec4> model(static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.height), glm::vec4(-1));
    for (std::size_t i = 0; i < s.points.size(); ++i) model[s.pixels[i]] = shade(v, p, o.terms, s.points[i], frame.light, s.samples_of(i));
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      const glm::vec3 drawn = drawn_colour(*frame.drawn, s.pixels[i]);
      failing += off(model[s.pixels[i]], drawn, o.threshold) && !near_neighbour(model, s.width, s.height, s.pixels[i], drawn, o.threshold);
    }
  }
  return static_cast<double>(failing) / static_cast<double>(s.points.size());
}

double squared_error(Variant v, const Parameters& p, const DrawnFrame& frame, const FitOptions& o) {
  const auto& s = *frame.surface;
  double sum = 0;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const glm::vec3 d = as_canvas_stores(shade(v, p, o.terms, s.points[i], frame.light, s.samples_of(i))) - drawn_colour(*frame.drawn, s.pixels[i]);
    sum += static_cast<double>(glm::dot(d, d));
  }
  return sum;
}

namespace {

double most_allowed(const std::vector<DrawnFrame>& frames) {
  double most = 0;
  for (const auto& frame : frames) most = std::max(most, frame.allowed);
  return most;
}

Fit sample_fit(Variant v, const Parameters& p, const std::vector<Sampled>& sample, const std::vector<Factors>& f, const FitOptions& o) {
  Fit fit{v, p, rms_of(sample, f, p, o.terms), sample_failing(sample, f, p, o)};
  fit.worst_failing = fit.sample_failing;
  for (const auto& factor : f) fit.specular_peak = std::max(fit.specular_peak, specular_factor(factor, p.exponent));
  return fit;
}

}  // namespace

std::vector<Fit> sample_fits(const std::vector<DrawnFrame>& frames, const FitOptions& o) {
  const std::vector<Sampled> sample = sample_of(frames, o.sample);
  const double margin = kSampleMargin * most_allowed(frames);
  std::vector<Fit> fits;
  for (const VariantInfo& v : variants()) {
    if (!applies_to(v, o.terms) || (o.only && v.variant != *o.only)) continue;
    std::vector<Factors> f;
    f.reserve(sample.size());
    for (const auto& s : sample) {
      const FrameSurface& surface = *frames[s.frame].surface;
      f.push_back(factors(v.variant, surface.points[s.point], frames[s.frame].light, surface.samples_of(s.point)));
    }
    // The normal's colour has no values to fit: each variant's one fit is what it draws.
    if (o.terms == Terms::normal_colour) {
      fits.push_back(sample_fit(v.variant, o.course, sample, f, o));
      continue;
    }
    if (Fit course = sample_fit(v.variant, o.course, sample, f, o); course.sample_failing <= margin) {
      course.course_values = true;
      fits.push_back(course);
    }
    Fit fitted = sample_fit(v.variant, fitted_values(design_of(sample, f, o), o).parameters, sample, f, o);
    // Only where the fitted values come close: the course's colours draw the sample no closer.
    if (o.terms == Terms::phong && fitted.sample_failing <= margin)
      if (const Trial kept = course_colours(sample, f, o); kept.parameters.exponent != o.course.exponent)
        fits.push_back(sample_fit(v.variant, kept.parameters, sample, f, o));
    fits.push_back(std::move(fitted));
  }
  return fits;
}

bool worth_checking(const Fit& fit, const std::vector<DrawnFrame>& frames) {
  return fit.sample_failing <= kSampleMargin * most_allowed(frames);
}

void check_pixels(Fit& fit, const std::vector<DrawnFrame>& frames, const FitOptions& o, Extent extent) {
  fit.worst_failing = 0;
  fit.reproduces = true;
  for (const auto& frame : frames) {
    const double share = failing_share(fit.variant, fit.parameters, frame, o);
    fit.worst_failing = std::max(fit.worst_failing, share);
    fit.reproduces = fit.reproduces && share <= frame.allowed;
    if (!fit.reproduces && extent == Extent::until_off) break;
  }
}

std::vector<Fit> fit_variants(const std::vector<DrawnFrame>& frames, const FitOptions& o) {
  const std::vector<Fit> candidates = sample_fits(frames, o);
  std::vector<Fit> fits;
  for (std::size_t i = 0; i < candidates.size();) {
    std::size_t end = i;  // the variant's candidates: its course values (where the sample allows), then its fitted ones
    while (end < candidates.size() && candidates[end].variant == candidates[i].variant) ++end;
    Fit chosen = candidates[end - 1];
    if (worth_checking(chosen, frames))
      for (std::size_t k = i; k < end; ++k) {
        chosen = candidates[k];
        check_pixels(chosen, frames, o, Extent::until_off);
        if (chosen.reproduces) break;
      }
    fits.push_back(chosen);
    i = end;
  }
  std::stable_sort(fits.begin(), fits.end(), [](const Fit& a, const Fit& b) {
    if (a.reproduces != b.reproduces) return a.reproduces;
    return a.rms < b.rms;
  });
  // The closest, where none reproduces, with how far off its worst frame is (what the student reads).
  if (Fit& closest = fits.front(); !closest.reproduces) check_pixels(closest, frames, o, Extent::whole);
  return fits;
}

Fit fit_light_position(const std::vector<DrawnFrame>& frames, const FitOptions& o) {
  const std::vector<Sampled> sample = sample_of(frames, o.sample);
  const auto factors_at = [&](const glm::vec3& light) {
    std::vector<Factors> f;
    f.reserve(sample.size());
    for (const auto& s : sample) f.push_back(factors(Variant::formula, frames[s.frame].surface->points[s.point], {light, frames[s.frame].light.colour}));
    return f;
  };
  const auto rms_at = [&](const glm::vec3& light) { return least_squares(design_of(sample, factors_at(light), o), o.course.exponent, o).rms; };
  const glm::vec3 page = frames.front().light.position;
  const float distance = std::max(1.0f, glm::length(page));
  std::vector<glm::vec3> starts = {page};
  for (const glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)})
    for (const float sign : {1.0f, -1.0f}) starts.push_back(sign * distance * axis);
  glm::vec3 best = page;
  double best_rms = rms_at(page);
  for (const auto& start : starts) {
    const glm::vec3 found = nelder_mead(rms_at, start, 0.25f * distance, 60);
    if (const double r = rms_at(found); r < best_rms) best = found, best_rms = r;
  }
  const auto f = factors_at(best);
  Trial t = least_squares(design_of(sample, f, o), o.course.exponent, o);
  t.parameters.light_position = best;
  Fit fit{Variant::formula, t.parameters, rms_of(sample, f, t.parameters, o.terms)};
  check_pixels(fit, frames, o, Extent::whole);
  for (const auto& factor : f) fit.specular_peak = std::max(fit.specular_peak, specular_factor(factor, o.course.exponent));
  return fit;
}

}  // namespace shadelab::model
