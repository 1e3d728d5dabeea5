#include "grade/formula_explanation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "core/words.h"
#include "grade/difference_regions.h"
#include "model/fit.h"

namespace shadelab::grade {

namespace {

// A colour the frames show as different: some channel off by more than 5/255. An exponent: more
// than 5% off (the fit finds the course's 6.0 to within 1% on its own reference).
constexpr float kColourTolerance = 0.02f;
constexpr double kExponentTolerance = 0.05;
// A reading's light position: 5% of each coordinate, as the fit finds a moved light.
constexpr double kPositionTolerance = 0.05;
// Explanations whose residual is within this factor of the best one's fit as well.
constexpr double kAsWell = 1.25;
// The most changes an explanation may make: a student's slip is one or two.
constexpr int kMostChanges = 2;

// The submission's value under one of the input's names, else the course's.
const render::UniformSetting* setting_of(const FormulaInput& in, const std::vector<render::UniformSetting>& values) {
  for (const auto& v : values)
    if (std::find(in.names.begin(), in.names.end(), v.name) != in.names.end() && v.values.size() >= 3) return &v;
  return nullptr;
}

std::array<float, 3> value_of(const FormulaInput& in, const std::vector<render::UniformSetting>& values) {
  const auto* v = setting_of(in, values);
  return v ? std::array<float, 3>{static_cast<float>(v->values[0]), static_cast<float>(v->values[1]), static_cast<float>(v->values[2])} : in.value;
}

float alpha_of(const FormulaInput& in, const std::vector<render::UniformSetting>& values) {
  const auto* v = setting_of(in, values);
  return v ? (v->values.size() >= 4 ? static_cast<float>(v->values[3]) : 1.0f) : in.alpha;
}

glm::vec3 vec(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }

std::string number(double v, const char* format = "%.2f") {
  char out[32];
  std::snprintf(out, sizeof out, format, std::abs(v) < 0.005 ? 0.0 : v);
  return out;
}

std::string triple(const glm::vec3& c) { return "(" + number(c.r) + ", " + number(c.g) + ", " + number(c.b) + ")"; }

bool near(const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 d = glm::abs(a - b);
  return std::max({d.r, d.g, d.b}) <= kColourTolerance;
}

// What an explanation changes, counted and said.
struct Reading {
  model::Fit* fit = nullptr;  // checked on every pixel in place (reproducing_readings)
  std::vector<Explanation::Parameter> parameters;
  std::vector<std::string> changes;  // a sentence each
  std::vector<std::string> labels;   // a few words each
  int count = 0;
};

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
  if (near(fitted, glm::vec3(0))) return "your " + term + " term is missing: its colour " + as;
  std::string words = "your " + term + " colour " + as;
  const glm::vec3 ratio = fitted / glm::max(course, glm::vec3(1e-3f));
  if (std::abs(ratio.r - ratio.g) < 0.05f * ratio.r && std::abs(ratio.r - ratio.b) < 0.05f * ratio.r && course.r > 0.05f)
    words += ", " + number(ratio.r, "%.1f") + " times it";
  return words;
}

std::string colour_label(const std::string& term, const glm::vec3& fitted) {
  return near(fitted, glm::vec3(0)) ? term + " term missing" : term + " colour changed";
}

std::string position(const glm::vec3& p) {
  return "(" + number(p.x, "%.1f") + ", " + number(p.y, "%.1f") + ", " + number(p.z, "%.1f") + ")";
}

Reading read(model::Fit& fit, const model::Parameters& course, const model::Light& page, const FormulaSpec& f) {
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
  const bool swapped = phong && !near(c.diffuse, c.specular) && near(p.diffuse, c.specular) && near(p.specular, c.diffuse);
  if (!near(p.ambient, c.ambient)) {
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
    if (!near(p.diffuse, c.diffuse)) {
      r.parameters.push_back(parameter(model::Parameter::diffuse, c.diffuse, p.diffuse));
      r.changes.push_back(colour_words("diffuse", f.diffuse, c.diffuse, p.diffuse));
      r.labels.push_back(colour_label("diffuse", p.diffuse));
      ++r.count;
    }
    if (phong && !near(p.specular, c.specular)) {
      r.parameters.push_back(parameter(model::Parameter::specular, c.specular, p.specular));
      r.changes.push_back(colour_words("specular", f.specular, c.specular, p.specular));
      r.labels.push_back(colour_label("specular", p.specular));
      ++r.count;
    }
  }
  const bool highlight_shows = phong && fit.specular_peak * std::max({p.specular.r, p.specular.g, p.specular.b}) > kColourTolerance;
  if (highlight_shows && std::abs(fit.parameters.exponent / course.exponent - 1) > kExponentTolerance) {
    r.parameters.push_back({std::string(to_string(model::Parameter::exponent)), {course.exponent}, {fit.parameters.exponent}});
    r.changes.push_back("your exponent acts as " + number(fit.parameters.exponent, "%.1f") + " where the course's " + f.exponent.variable +
                        " is " + number(course.exponent, "%.1f"));
    r.labels.emplace_back("exponent changed");
    ++r.count;
  }
  return r;
}

// A frame's middle colour, channel by channel: the median of its interior pixels.
glm::vec3 median_colour(const model::DrawnFrame& f) {
  std::array<std::array<std::size_t, 256>, 3> counts{};
  for (const std::uint32_t pixel : f.surface->pixels)
    for (int ch = 0; ch < 3; ++ch) ++counts[ch][f.drawn->bytes[static_cast<std::size_t>(pixel) * 4 + ch]];
  glm::vec3 out(0);
  for (int ch = 0; ch < 3; ++ch)
    for (std::size_t value = 0, seen = 0; value < 256; ++value)
      if (seen += counts[ch][value]; 2 * seen > f.surface->pixels.size()) {
        out[ch] = static_cast<float>(value) / 255;
        break;
      }
  return out;
}

// The student's object's colour, where it is one: every frame's interior pixels within the
// threshold of the first frame's middle colour, but the share a frame may differ (in another
// rasteriser's frames, an outline a pixel away). No term that depends on the light shows, and no
// fit can say which is missing.
std::optional<glm::vec3> one_colour(const std::vector<model::DrawnFrame>& frames, double threshold) {
  if (frames.empty() || frames.front().surface->pixels.empty()) return std::nullopt;
  const glm::vec3 colour = median_colour(frames.front());
  for (const auto& f : frames) {
    std::size_t off = 0;
    for (const std::uint32_t pixel : f.surface->pixels) {
      const std::uint8_t* p = f.drawn->bytes.data() + static_cast<std::size_t>(pixel) * 4;
      const glm::vec3 d = glm::abs(glm::vec3(p[0], p[1], p[2]) / 255.0f - colour);
      off += std::max({d.r, d.g, d.b}) > threshold;
    }
    if (static_cast<double>(off) > f.allowed * static_cast<double>(f.surface->pixels.size())) return std::nullopt;
  }
  return colour;
}

std::string joined(const std::vector<std::string>& sentences) {
  std::string out;
  for (const auto& s : sentences) out += (out.empty() ? "" : "; and ") + s;
  return out;
}

std::string where_they_differ(const std::string& text, const std::vector<RegionDifference>& regions) {
  if (regions.empty()) return text;
  std::vector<std::string> where;
  for (const auto& r : regions) where.push_back(to_words(r));
  return text + " Where your frames differ from the reference: " + comma_list(where) + ".";
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
      if (Reading r = read(c, o.course, page, f); r.count <= kMostChanges) offered.push_back(std::move(r));
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

// The frames as the fit sees them, light after light, each allowed the rule's share plus what the
// formula itself leaves off of the reference's frame there (the model's, not the student's); and
// the worst of the latter.
struct Framed {
  std::vector<model::DrawnFrame> frames;
  double worst_model_error = 0;
};
Framed drawn_frames(const FormulaEvidence& e, const std::vector<model::Light>& lights, const model::FitOptions& o, const GradeOptions& options) {
  const std::vector<model::FrameSurface>& averaged = *e.surfaces;
  const std::size_t n = averaged.size();
  Framed out;
  for (std::size_t l = 0; l < lights.size(); ++l)
    for (std::size_t k = 0; k < n && l * n + k < e.student->size() && l * n + k < e.reference->size(); ++k) {
      const model::DrawnFrame reference{&averaged[k], (*e.reference)[l * n + k].get(), lights[l]};
      const double model_error = model::failing_share(model::Variant::formula, o.course, reference, o);
      out.worst_model_error = std::max(out.worst_model_error, model_error);
      out.frames.push_back({&averaged[k], (*e.student)[l * n + k].get(), lights[l], options.max_failing_fraction + model_error});
    }
  return out;
}

// The explanation the best reading gives (readings in the order offered), and those that fit as well.
Explanation explained_by(const std::vector<Reading>& readings) {
  const Reading& best = readings.front();
  Explanation out;
  out.explained = true;
  out.variant = std::string(model::info(best.fit->variant).id);
  out.parameters = best.parameters;
  out.residual = best.fit->worst_failing;
  for (const auto& l : best.labels) out.label += (out.label.empty() ? "" : " + ") + l;
  out.text = "Your frames are the homework's formula with " + std::string(best.count == 1 ? "one change" : "two changes") + ": " +
             joined(best.changes) + ". (This reproduces every frame but " + percent(best.fit->worst_failing, 1) + " of its pixels at most.)";
  for (std::size_t i = 1; i < readings.size(); ++i)
    if (as_well(readings[i], best)) {
      out.also_fits.push_back(std::string(model::info(readings[i].fit->variant).id));
      out.text += " It fits as well: " + joined(readings[i].changes) + ".";
    }
  return out;
}

}  // namespace

model::Parameters course_parameters(const FormulaSpec& f, const std::vector<render::UniformSetting>& values) {
  return {{vec(value_of(f.ambient, values)), vec(value_of(f.diffuse, values)), vec(value_of(f.specular, values)),
           {alpha_of(f.ambient, values), alpha_of(f.diffuse, values), alpha_of(f.specular, values)}},
          static_cast<float>(f.exponent.value)};
}

std::vector<model::Light> formula_lights(const FormulaSpec& f, const std::vector<render::UniformSetting>& values,
                                         const std::vector<Probe>& probes) {
  const model::Light page{vec(value_of(f.light_position, values)), vec(value_of(f.light_colour, values))};
  std::vector<model::Light> lights = {page};
  for (const auto& p : probes)
    lights.push_back({p.light_position ? vec(*p.light_position) : page.position, p.light_color ? vec(*p.light_color) : page.colour});
  return lights;
}

FormulaRead explain_with_formula(const FormulaEvidence& e, const GradeOptions& options) {
  const FormulaSpec& f = *e.formula;
  model::FitOptions o;
  o.terms = f.terms;
  o.course = course_parameters(f, e.values);
  o.threshold = options.compare.threshold;
  o.spatial_tolerance = options.compare.spatial_tolerance;
  const auto lights = formula_lights(f, e.values, e.probes);
  const std::vector<model::FrameSurface>* geometry = e.surfaces;
  const std::size_t n = geometry->size();
  Framed framed = drawn_frames(e, lights, o, options);
  std::vector<model::DrawnFrame>& frames = framed.frames;
  const double worst_model_error = framed.worst_model_error;

  Explanation out;
  const auto regions = [&] { return difference_regions(*geometry, *e.student, *e.reference, lights.front(), o); };
  // Where the formula cannot draw the reference itself within the rule (frames so small that a
  // pixel holds many triangles), what it finds in the student's frames is not to be trusted.
  if (worst_model_error > options.max_failing_fraction) {
    out.text = where_they_differ("The grader cannot read frames this small by the homework's formula: its own drawing of the reference is off on " +
                                     percent(worst_model_error, 1) + " of a frame's pixels, more than the " +
                                     percent(options.max_failing_fraction) + " a frame may differ.",
                                 regions());
    out.label = "frames too small to read";
    return {out, {}};
  }
  const bool lit = f.terms != model::Terms::normal_colour;
  if (const auto colour = one_colour(frames, o.threshold); colour && (!lit || !near(*colour, o.course.colours.ambient))) {
    out.text = "Your object is one colour, " + triple(*colour) + ", everywhere: " +
               (lit ? "no term that depends on the light shows, so the grader cannot say which part of the formula is missing."
                    : "the homework's colour follows the normal, normalize(abs(N)), and changes across the surface.");
    out.label = "one colour";
    return {out, {}};
  }
  std::vector<model::Fit> candidates = model::sample_fits(frames, o);
  std::vector<Reading> readings = reproducing_readings(candidates, frames, o, lights.front(), f);
  const auto one_change = [&] { return std::any_of(readings.begin(), readings.end(), [](const Reading& r) { return r.count == 1; }); };
  // One variant read again on other geometry, every frame moved to it (the averaged set may leave
  // the worker's memory as the other comes in): its readings join the rest.
  const auto read_again_on = [&](const std::vector<model::FrameSurface>& on, model::Variant only, std::vector<model::Fit>& fits) {
    geometry = &on;
    for (std::size_t i = 0; i < frames.size(); ++i) frames[i].surface = &on[i % n];
    model::FitOptions one = o;
    one.only = only;
    fits = model::sample_fits(frames, one);
    auto more = reproducing_readings(fits, frames, one, lights.front(), f);
    readings.insert(readings.end(), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
    std::stable_sort(readings.begin(), readings.end(), before);
  };
  // Flat normals shade a pixel's samples apart, and its highlight is the mean of their shades: read
  // on each sample's flat normal, four renders more, fetched only when no one change of the
  // averaged geometry explains the frames.
  std::vector<model::Fit> flat;
  if (!one_change() && e.sampled)
    if (const auto* sampled = e.sampled(); sampled && sampled->size() == n) read_again_on(*sampled, model::Variant::flat_normal, flat);
  // A flat colour in saved frames, close but off by more than the rule allows: read again with
  // the angles of the frames it leaves off placed by the triangles' edges, two renders of them.
  std::optional<EdgePlacement> placed;
  std::vector<model::Fit> placed_fits;
  if (!one_change() && e.moved_flat_colour)
    if (const auto close = std::find_if(candidates.begin(), candidates.end(), [&](const model::Fit& c) {
          return c.variant == model::Variant::flat_colour && !c.reproduces && model::worth_checking(c, frames);
        });
        close != candidates.end())
      if ((placed = placed_by_edges(*close, frames, n, o, e.moved_flat_colour))) read_again_on(placed->surfaces, model::Variant::flat_colour, placed_fits);
  // A light the student moved (written into the shader) is looked for only when no single change
  // of the rest explains the frames: its search costs more than every variant's together. The
  // normal's colour has no light.
  model::Fit moved_light;
  if (lit && !one_change()) {
    moved_light = model::fit_light_position(frames, o);
    if (moved_light.reproduces)
      if (Reading r = read(moved_light, o.course, lights.front(), f); r.count <= kMostChanges) readings.push_back(std::move(r));
    std::stable_sort(readings.begin(), readings.end(), before);
  }

  if (readings.empty()) {
    const model::Fit& closest = closest_fit(candidates, frames, o);
    out.variant = std::string(model::info(closest.variant).id);
    out.residual = closest.worst_failing;
    out.text = where_they_differ("The grader cannot say why from the homework's formula: no change of one or two of its parts reproduces your "
                                 "frames (the closest leaves " + percent(closest.worst_failing, 1) + " of a frame's pixels off).",
                                 regions());
    out.label = "not explained";
    return {out, {}};
  }
  const Reading& best = readings.front();
  const bool on_placed = placed && !placed_fits.empty() && best.fit >= placed_fits.data() && best.fit < placed_fits.data() + placed_fits.size();
  return {explained_by(readings), on_placed ? placed->offsets : std::vector<double>{}};
}

namespace {

// Whether a fitted value is a reading's, within what the frames tell apart: a colour's step, the
// exponent's 5%, a position's 5% of each coordinate (of 1 at least).
bool close_enough(model::Parameter parameter, double fitted, double wanted) {
  const double off = std::abs(fitted - wanted);
  switch (parameter) {
    case model::Parameter::exponent: return off <= kExponentTolerance * wanted;
    case model::Parameter::light_position: return off <= kPositionTolerance * std::max(1.0, std::abs(wanted));
    default: return off <= kColourTolerance;
  }
}

}  // namespace

bool reads_as(const Explanation& e, const FormulaReading& reading) {
  const std::string variant(model::info(reading.variant).id);
  const bool also = reading.values.empty() && std::find(e.also_fits.begin(), e.also_fits.end(), variant) != e.also_fits.end();
  if (!e.explained || (e.variant != variant && !also) || e.parameters.size() != reading.values.size()) return false;
  for (const auto& want : reading.values) {
    const auto found = std::find_if(e.parameters.begin(), e.parameters.end(),
                                    [&](const Explanation::Parameter& p) { return p.name == to_string(want.parameter); });
    if (found == e.parameters.end() || found->fitted.size() != want.value.size()) return false;
    for (std::size_t i = 0; i < want.value.size(); ++i)
      if (!close_enough(want.parameter, found->fitted[i], want.value[i])) return false;
  }
  return true;
}

CatalogueWork catalogue_work(const std::vector<Mistake>& mistakes, const std::optional<Explanation>& e) {
  CatalogueWork out;
  for (const auto& m : mistakes) {
    if (!e || !e->explained || !m.reading) out.to_render.push_back(&m);
    else if (!out.recognised && reads_as(*e, *m.reading)) out.recognised = &m;
  }
  return out;
}

std::optional<RenderedMistake> recognised_mistake(const CatalogueWork& work) {
  if (!work.recognised) return std::nullopt;
  return RenderedMistake{work.recognised->id, work.recognised->message, {}};
}

void say_explanation(Report& report) {
  if (!report.explanation || !report.diagnosis.empty()) return;
  auto& m = report.messages;
  m.insert(report.explanation->explained ? m.begin() : m.end(), report.explanation->text);
}

}  // namespace shadelab::grade
