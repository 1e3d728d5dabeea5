#include "grade/formula_readings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace shadelab::grade {

namespace {

// The submission's value under one of the input's names, else the course's.
const render::UniformSetting* setting_of(const FormulaInput& in, const std::vector<render::UniformSetting>& values) {
  for (const auto& v : values)
    if (std::find(in.names.begin(), in.names.end(), v.name) != in.names.end() && v.values.size() >= 3) return &v;
  return nullptr;
}


std::string first_name(const FormulaInput& in) { return in.names.empty() ? std::string("?") : in.names.front(); }

std::string filled(std::string_view words, const FormulaSpec& f) {
  std::string out(words);
  const std::pair<std::string, std::string> names[] = {{"{light}", first_name(f.light_position)},
                                                       {"{light colour}", first_name(f.light_colour)},
                                                       {"{position}", f.position_varying},
                                                       {"{normal}", f.normal_varying},
                                                       {"{colour}", f.colour_varying}};
  for (const auto& [from, to] : names)
    for (std::size_t at = out.find(from); at != std::string::npos; at = out.find(from, at + to.size())) out.replace(at, from.size(), to);
  return out;
}

Explanation::Parameter parameter(model::Parameter name, const glm::vec3& course, const glm::vec3& fitted) {
  return {std::string(to_string(name)), {course.r, course.g, course.b}, {fitted.r, fitted.g, fitted.b}};
}

// "your ambient colour acts as (0.40, 0.20, 0.20) where the course's uAmbientColor is (0.20, 0.10, 0.10), 2.0 times it"
std::string colour_words(const std::string& term, const FormulaInput& in, const glm::vec3& course, const glm::vec3& fitted) {
  const std::string as = "acts as " + triple(fitted) + " where the course's " + first_name(in) + " is " + triple(course);
  if (colours_near(fitted, glm::vec3(0))) return "your " + term + " term is missing: its colour " + as;
  std::string words = "your " + term + " colour " + as;
  const glm::vec3 ratio = fitted / glm::max(course, glm::vec3(1e-3f));
  if (std::abs(ratio.r - ratio.g) < 0.05f * ratio.r && std::abs(ratio.r - ratio.b) < 0.05f * ratio.r && course.r > 0.05f)
    words += ", " + number_text(ratio.r, "%.1f") + " times it";
  return words;
}

std::string colour_label(const std::string& term, const glm::vec3& fitted) {
  return colours_near(fitted, glm::vec3(0)) ? term + " term missing" : term + " colour changed";
}

std::string position(const glm::vec3& p) {
  return "(" + number_text(p.x, "%.1f") + ", " + number_text(p.y, "%.1f") + ", " + number_text(p.z, "%.1f") + ")";
}

}  // namespace

std::array<float, 3> value_of(const FormulaInput& in, const std::vector<render::UniformSetting>& values) {
  const auto* v = setting_of(in, values);
  return v ? std::array<float, 3>{static_cast<float>(v->values[0]), static_cast<float>(v->values[1]), static_cast<float>(v->values[2])} : in.value;
}

float alpha_of(const FormulaInput& in, const std::vector<render::UniformSetting>& values) {
  const auto* v = setting_of(in, values);
  return v ? (v->values.size() >= 4 ? static_cast<float>(v->values[3]) : 1.0f) : in.alpha;
}

glm::vec3 as_vec3(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }

std::string number_text(double v, const char* format) {
  char out[32];
  std::snprintf(out, sizeof out, format, std::abs(v) < 0.005 ? 0.0 : v);
  return out;
}

std::string triple(const glm::vec3& c) { return "(" + number_text(c.r) + ", " + number_text(c.g) + ", " + number_text(c.b) + ")"; }

bool colours_near(const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 d = glm::abs(a - b);
  return std::max({d.r, d.g, d.b}) <= kColourTolerance;
}

Reading reading_of(model::Fit& fit, const model::Parameters& course, const model::Light& page, const FormulaSpec& f) {
  Reading r{&fit};
  if (const auto& at = fit.parameters.light_position) {
    r.parameters.push_back(parameter(model::Parameter::light_position, page.position, *at));
    r.changes.push_back("your light acts as if at " + position(*at) + " under every light the grader draws, where the course's " +
                        first_name(f.light_position) + " is " + position(page.position) + ": L must point to " +
                        first_name(f.light_position) + ", the light the page sets; a position written into the shader ignores it");
    r.labels.emplace_back("light moved");
    ++r.count;
  }
  if (fit.variant != model::Variant::formula) {
    const auto& v = model::info(fit.variant);
    r.changes.push_back(filled(v.does, f) + ": " + filled(v.should, f));
    r.labels.emplace_back(v.label);
    ++r.count;
  }
  const auto& c = course.colours;
  const auto& p = fit.parameters.colours;
  const bool phong = f.terms == model::Terms::phong;
  const bool swapped = phong && !colours_near(c.diffuse, c.specular) && colours_near(p.diffuse, c.specular) && colours_near(p.specular, c.diffuse);
  if (!colours_near(p.ambient, c.ambient)) {
    r.parameters.push_back(parameter(model::Parameter::ambient, c.ambient, p.ambient));
    r.changes.push_back(colour_words("ambient", f.ambient, c.ambient, p.ambient));
    r.labels.push_back(colour_label("ambient", p.ambient));
    ++r.count;
  }
  if (swapped) {
    r.parameters.push_back(parameter(model::Parameter::diffuse, c.diffuse, p.diffuse));
    r.parameters.push_back(parameter(model::Parameter::specular, c.specular, p.specular));
    r.changes.push_back("your diffuse and specular colours are swapped: the diffuse acts as " + triple(p.diffuse) + ", the course's " +
                        first_name(f.specular) + ", and the specular as " + triple(p.specular) + ", its " + first_name(f.diffuse));
    r.labels.emplace_back("diffuse and specular colours swapped");
    ++r.count;
  } else {
    if (!colours_near(p.diffuse, c.diffuse)) {
      r.parameters.push_back(parameter(model::Parameter::diffuse, c.diffuse, p.diffuse));
      r.changes.push_back(colour_words("diffuse", f.diffuse, c.diffuse, p.diffuse));
      r.labels.push_back(colour_label("diffuse", p.diffuse));
      ++r.count;
    }
    if (phong && !colours_near(p.specular, c.specular)) {
      r.parameters.push_back(parameter(model::Parameter::specular, c.specular, p.specular));
      r.changes.push_back(colour_words("specular", f.specular, c.specular, p.specular));
      r.labels.push_back(colour_label("specular", p.specular));
      ++r.count;
    }
  }
  const bool highlight_shows = phong && fit.specular_peak * std::max({p.specular.r, p.specular.g, p.specular.b}) > kColourTolerance;
  if (highlight_shows && std::abs(fit.parameters.exponent / course.exponent - 1) > kExponentTolerance) {
    r.parameters.push_back({std::string(to_string(model::Parameter::exponent)), {course.exponent}, {fit.parameters.exponent}});
    r.changes.push_back("your exponent acts as " + number_text(fit.parameters.exponent, "%.1f") + " where the course's " + f.exponent.variable +
                        " is " + number_text(course.exponent, "%.1f"));
    r.labels.emplace_back("exponent changed");
    ++r.count;
  }
  return r;
}

// The order explanations are offered in: the fewest changes first; of as many, values changed
// before the formula's structure (frames with no highlight in view fit "the specular term is
// missing" and a view vector that points away alike: the missing term is the likelier slip, and
// both are said), a variant's course values before its fitted ones; then the closest.
bool before(const Reading& a, const Reading& b) {
  const auto structural = [](const Reading& r) { return r.fit->variant != model::Variant::formula; };
  if (a.count != b.count) return a.count < b.count;
  if (structural(a) != structural(b)) return !structural(a);
  if (a.fit->course_values != b.fit->course_values) return a.fit->course_values;
  return a.fit->rms < b.fit->rms;
}

// Whether a reading is said beside the best one: as many changes, and as close (kAsWell).
bool as_well(const Reading& r, const Reading& best) { return r.count == best.count && r.fit->rms <= kAsWell * best.fit->rms; }

// The readings that reproduce the frames: the best, then those that fit as well. Each fit is
// checked on every pixel only when it could still be one of them, in the order they are offered:
// a check is the explanation's cost (a frame's every pixel, each frame), and frames with the
// specular term missing are reproduced by every change to the specular's direction alike. A
// variant is settled by its first fit that reproduces (its course values, where they do): a
// variant with no change (the formula with the course's values) is no reading.
std::vector<Reading> reproducing_readings(std::vector<model::Fit>& candidates, const std::vector<model::DrawnFrame>& frames,
                                          const model::FitOptions& o, const model::Light& page, const FormulaSpec& f) {
  std::vector<Reading> offered;
  for (auto& c : candidates)
    if (model::worth_checking(c, frames))
      if (Reading r = reading_of(c, o.course, page, f); r.count <= kMostChanges) offered.push_back(std::move(r));
  std::stable_sort(offered.begin(), offered.end(), before);
  std::vector<Reading> out;
  std::vector<model::Variant> settled;
  for (auto& r : offered) {
    if (!out.empty() && r.count != out.front().count) break;
    if (std::find(settled.begin(), settled.end(), r.fit->variant) != settled.end() || (!out.empty() && !as_well(r, out.front()))) continue;
    model::Fit& fit = *r.fit;
    model::check_pixels(fit, frames, o, model::Extent::until_off);
    if (!fit.reproduces) continue;
    settled.push_back(fit.variant);
    if (r.count > 0) out.push_back(std::move(r));
  }
  return out;
}

// The fit a student is told is closest where no reading reproduces the frames, checked whole:
// one that reproduces with too many changes (or none), else the fitted values closest on the sample.
const model::Fit& closest_fit(std::vector<model::Fit>& candidates, const std::vector<model::DrawnFrame>& frames, const model::FitOptions& o) {
  model::Fit* closest = nullptr;
  for (auto& c : candidates)
    if ((c.reproduces || !c.course_values) && (!closest || (c.reproduces != closest->reproduces ? c.reproduces : c.rms < closest->rms))) closest = &c;
  check_pixels(*closest, frames, o, model::Extent::whole);
  return *closest;
}

}  // namespace shadelab::grade
