#include "model/least_squares.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace shadelab::model {

namespace {

// A colour the canvas clamped tells only a bound: left out of the least squares.
bool clamped(float c) { return c <= 0.5f / 255 || c >= 254.5f / 255; }

}  // namespace

// The colours that best reproduce the sample at exponent `alpha`, channel by channel: least
// squares on (ambient, diffuse, specular), pulled weakly towards the course's values so that a
// colour the frames do not show (no highlight in view) stays the course's. The residual comes from
// the normal equations, with no second pass over the sample.
Trial least_squares(const Design& design, float alpha, const FitOptions& o) {
  const bool phong = o.terms == Terms::phong;
  Trial t{o.course, 0};
  t.parameters.exponent = alpha;
  std::vector<float> s(design.rows.size(), 0.0f);
  if (phong)
    for (std::size_t i = 0; i < s.size(); ++i) {
      const auto& r = design.rows[i];
      for (std::size_t k = 0; k < static_cast<std::size_t>(r.samples); ++k) s[i] += std::exp(alpha * r.log_cosine[k]);
      if (r.samples > 1) s[i] /= static_cast<float>(r.samples);
    }
  const double ridge = 1e-4 * static_cast<double>(design.rows.size());
  double residual = 0, used = 0;
  for (int ch = 0; ch < 3; ++ch) {
    glm::dmat3 ata(0.0);
    glm::dvec3 atb(0.0);
    double ctc = 0, n = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const auto& r = design.rows[i];
      if (!r.used[ch]) continue;
      const glm::dvec3 row(1.0, r.diffuse[ch], phong ? r.specular[ch] * s[i] : 0.0f);
      const double c = r.drawn[ch];
      ata += glm::outerProduct(row, row);
      atb += row * c;
      ctc += c * c, n += 1;
    }
    const auto& k = o.course.colours;
    const glm::dvec3 prior(k.ambient[ch], k.diffuse[ch], k.specular[ch]);
    glm::dmat3 regular = ata;
    for (int r = 0; r < 3; ++r) regular[r][r] += ridge;
    const glm::dvec3 x = glm::inverse(regular) * (atb + ridge * prior);
    residual += std::max(0.0, ctc - 2 * glm::dot(x, atb) + glm::dot(x, ata * x));
    used += n;
    t.parameters.colours.ambient[ch] = static_cast<float>(x[0]);
    t.parameters.colours.diffuse[ch] = static_cast<float>(x[1]);
    if (phong) t.parameters.colours.specular[ch] = static_cast<float>(x[2]);
  }
  t.rms = used > 0 ? std::sqrt(residual / used) : 0;
  return t;
}

Design design_of(const std::vector<Sampled>& sample, const std::vector<Factors>& f, const FitOptions& o) {
  Design d;
  d.rows.reserve(sample.size());
  for (std::size_t i = 0; i < sample.size(); ++i) {
    const Factors& x = f[i];
    // The alpha before the specular term (which only adds to it): under 1, the canvas divides.
    const bool divided = o.course.colours.alpha[0] + o.course.colours.alpha[1] * x.d < 1;
    Design::Row r{x.diffuse_light * x.d, x.specular_light, {}, x.samples, sample[i].drawn, {}};
    for (std::size_t k = 0; k < static_cast<std::size_t>(x.samples); ++k) {
      const SpecularSample& at = x.specular[k];
      r.log_cosine[k] = at.on && at.c > 0 ? std::log(at.c) : -std::numeric_limits<float>::infinity();
    }
    for (int ch = 0; ch < 3; ++ch) r.used[ch] = !divided && !clamped(sample[i].drawn[ch]);
    d.rows.push_back(r);
  }
  return d;
}

Trial best_exponent(const ExponentTrial& trial, const FitOptions& o) {
  Trial best = trial(o.course.exponent);
  if (o.terms != Terms::phong) return best;
  std::vector<float> grid;
  for (float a = 0.5f; a <= 256.0f; a *= std::cbrt(2.0f)) grid.push_back(a);
  std::size_t at = grid.size();
  for (std::size_t i = 0; i < grid.size(); ++i)
    if (Trial t = trial(grid[i]); t.rms < best.rms) best = t, at = i;
  if (at == grid.size()) return best;  // the course's own exponent is best
  double lo = std::log(grid[at > 0 ? at - 1 : 0]), hi = std::log(grid[std::min(at + 1, grid.size() - 1)]);
  const double g = (std::sqrt(5.0) - 1) / 2;
  double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
  Trial ta = trial(static_cast<float>(std::exp(a))), tb = trial(static_cast<float>(std::exp(b)));
  for (int step = 0; step < 20; ++step) {
    if (ta.rms < tb.rms) {
      hi = b, b = a, tb = ta, a = hi - g * (hi - lo);
      ta = trial(static_cast<float>(std::exp(a)));
    } else {
      lo = a, a = b, ta = tb, b = lo + g * (hi - lo);
      tb = trial(static_cast<float>(std::exp(b)));
    }
    if (ta.rms < best.rms) best = ta;
    if (tb.rms < best.rms) best = tb;
  }
  return best;
}

Trial fitted_values(const Design& design, const FitOptions& o) {
  return best_exponent([&](float alpha) { return least_squares(design, alpha, o); }, o);
}

}  // namespace shadelab::model
