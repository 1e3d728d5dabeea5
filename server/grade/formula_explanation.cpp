#include "grade/formula_explanation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <optional>
#include <string_view>

#include "core/words.h"
#include "grade/difference_regions.h"
#include "grade/formula_readings.h"
#include "model/fit.h"

namespace shadelab::grade {

namespace {

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
  return {{as_vec3(value_of(f.ambient, values)), as_vec3(value_of(f.diffuse, values)), as_vec3(value_of(f.specular, values)),
           {alpha_of(f.ambient, values), alpha_of(f.diffuse, values), alpha_of(f.specular, values)}},
          static_cast<float>(f.exponent.value)};
}

std::vector<model::Light> formula_lights(const FormulaSpec& f, const std::vector<render::UniformSetting>& values,
                                         const std::vector<Probe>& probes) {
  const model::Light page{as_vec3(value_of(f.light_position, values)), as_vec3(value_of(f.light_colour, values))};
  std::vector<model::Light> lights = {page};
  for (const auto& p : probes)
    lights.push_back({p.light_position ? as_vec3(*p.light_position) : page.position, p.light_color ? as_vec3(*p.light_color) : page.colour});
  return lights;
}

namespace {

// What the reading holds while its stages run: the frames as the fit sees them (on the geometry
// read last), and the readings found so far. Fits live in `fit_sets` (a deque: a stage's new set
// leaves the readings' pointers into the earlier ones valid).
struct ReadingState {
  const FormulaEvidence& e;
  const GradeOptions& options;
  const FormulaSpec& f;
  model::FitOptions o;
  std::vector<model::Light> lights;
  const std::vector<model::FrameSurface>* geometry = nullptr;
  std::size_t n = 0;  // frames a light
  std::vector<model::DrawnFrame> frames;
  double worst_model_error = 0;
  bool lit = true;
  std::deque<std::vector<model::Fit>> fit_sets;  // the averaged geometry's first
  std::vector<Reading> readings;
  std::optional<EdgePlacement> placed;                    // the flat colour's frames placed by their edges
  const std::vector<model::Fit>* placed_fits = nullptr;  // the fits read on them

  bool one_change() const { return std::any_of(readings.begin(), readings.end(), [](const Reading& r) { return r.count == 1; }); }
  std::vector<RegionDifference> regions() const { return difference_regions(*geometry, *e.student, *e.reference, lights.front(), o); }

  // One variant read on other geometry, every frame moved to it (the averaged set may leave the
  // worker's memory as the other comes in): its readings join the rest. Returns its fits.
  const std::vector<model::Fit>& read_again_on(const std::vector<model::FrameSurface>& on, model::Variant only) {
    geometry = &on;
    for (std::size_t i = 0; i < frames.size(); ++i) frames[i].surface = &on[i % n];
    model::FitOptions one = o;
    one.only = only;
    std::vector<model::Fit>& fits = fit_sets.emplace_back(model::sample_fits(frames, one));
    auto more = reproducing_readings(fits, frames, one, lights.front(), f);
    readings.insert(readings.end(), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
    std::stable_sort(readings.begin(), readings.end(), before);
    return fits;
  }
};

ReadingState start_reading(const FormulaEvidence& e, const GradeOptions& options) {
  ReadingState s{e, options, *e.formula, {}, {}, e.surfaces, e.surfaces->size()};
  s.o.terms = s.f.terms;
  s.o.course = course_parameters(s.f, e.values);
  s.o.threshold = options.compare.threshold;
  s.o.spatial_tolerance = options.compare.spatial_tolerance;
  s.lights = formula_lights(s.f, e.values, e.probes);
  Framed framed = drawn_frames(e, s.lights, s.o, options);
  s.frames = std::move(framed.frames);
  s.worst_model_error = framed.worst_model_error;
  s.lit = s.f.terms != model::Terms::normal_colour;
  return s;
}

// Each stage reads the frames one way; an explanation it returns ends the reading (the frames
// cannot be read), none goes on to the next.
using StageRead = std::optional<Explanation> (*)(ReadingState&);
using StageApplies = bool (*)(const ReadingState&);

// Where the formula cannot draw the reference itself within the rule (frames so small that a
// pixel holds many triangles), what it finds in the student's frames is not to be trusted.
std::optional<Explanation> formula_draws_the_reference(ReadingState& s) {
  if (s.worst_model_error <= s.options.max_failing_fraction) return std::nullopt;
  Explanation out;
  out.text = where_they_differ("The grader cannot read frames this small by the homework's formula: its own drawing of the reference is off on " +
                                   percent(s.worst_model_error, 1) + " of a frame's pixels, more than the " +
                                   percent(s.options.max_failing_fraction) + " a frame may differ.",
                               s.regions());
  out.label = "frames too small to read";
  return out;
}

std::optional<Explanation> one_colour_everywhere(ReadingState& s) {
  const auto colour = one_colour(s.frames, s.o.threshold);
  if (!colour || (s.lit && colours_near(*colour, s.o.course.colours.ambient))) return std::nullopt;
  Explanation out;
  out.text = "Your object is one colour, " + triple(*colour) + ", everywhere: " +
             (s.lit ? "no term that depends on the light shows, so the grader cannot say which part of the formula is missing."
                    : "the homework's colour follows the normal, normalize(abs(N)), and changes across the surface.");
  out.label = "one colour";
  return out;
}

std::optional<Explanation> every_variant(ReadingState& s) {
  std::vector<model::Fit>& candidates = s.fit_sets.emplace_back(model::sample_fits(s.frames, s.o));
  s.readings = reproducing_readings(candidates, s.frames, s.o, s.lights.front(), s.f);
  return std::nullopt;
}

// Flat normals shade a pixel's samples apart, and its highlight is the mean of their shades.
std::optional<Explanation> flat_normals_sample_by_sample(ReadingState& s) {
  if (const auto* sampled = s.e.sampled(); sampled && sampled->size() == s.n) s.read_again_on(*sampled, model::Variant::flat_normal);
  return std::nullopt;
}

// A flat colour in saved frames, close but off by more than the rule allows: read again with the
// angles of the frames it leaves off placed by the triangles' edges.
std::optional<Explanation> flat_colour_placed_by_edges(ReadingState& s) {
  std::vector<model::Fit>& candidates = s.fit_sets.front();
  const auto close = std::find_if(candidates.begin(), candidates.end(), [&](const model::Fit& c) {
    return c.variant == model::Variant::flat_colour && !c.reproduces && model::worth_checking(c, s.frames);
  });
  if (close == candidates.end()) return std::nullopt;
  if ((s.placed = placed_by_edges(*close, s.frames, s.n, s.o, s.e.moved_flat_colour)))
    s.placed_fits = &s.read_again_on(s.placed->surfaces, model::Variant::flat_colour);
  return std::nullopt;
}

// A light the student moved (written into the shader).
std::optional<Explanation> moved_light(ReadingState& s) {
  std::vector<model::Fit>& fit = s.fit_sets.emplace_back();
  fit.push_back(model::fit_light_position(s.frames, s.o));
  if (fit.front().reproduces)
    if (Reading r = reading_of(fit.front(), s.o.course, s.lights.front(), s.f); r.count <= kMostChanges) s.readings.push_back(std::move(r));
  std::stable_sort(s.readings.begin(), s.readings.end(), before);
  return std::nullopt;
}

bool always(const ReadingState&) { return true; }
bool no_one_change_and_samples(const ReadingState& s) { return !s.one_change() && s.e.sampled; }
bool no_one_change_and_saved_frames(const ReadingState& s) { return !s.one_change() && s.e.moved_flat_colour; }
bool no_one_change_and_lit(const ReadingState& s) { return s.lit && !s.one_change(); }

// The formula's reading, stage by stage in this order (docs/grading.md, "What the formula reads
// and what it costs"). The next reading is a row: where it applies, what it reads, what it costs.
struct Stage {
  std::string_view name;
  StageApplies applies;
  std::string_view reads;
  std::string_view costs;
  StageRead read;
};
const Stage kStages[] = {
    {"the formula draws the reference", always, "the reference's frames drawn by the formula with the course's values",
     "a pass over the frames", formula_draws_the_reference},
    {"one colour everywhere", always, "the student's frames' interior pixels against one colour", "a pass over the frames",
     one_colour_everywhere},
    {"every variant", always, "each of the model's variants fitted on a sample of the averaged geometry; a candidate that could explain "
     "checked pixel by pixel, fewest changes first", "the fits on the sample, a pixel check a candidate", every_variant},
    {"flat normals sample by sample", no_one_change_and_samples, "the flat-normal variant on each MSAA sample's flat normal, the "
     "samples' shades averaged", "four renders of the geometry (kept with the references)", flat_normals_sample_by_sample},
    {"a flat colour placed by its edges", no_one_change_and_saved_frames, "the flat-colour variant on saved frames moved to where "
     "their triangles' edges place them", "two renders of the frames it leaves off", flat_colour_placed_by_edges},
    {"a moved light", no_one_change_and_lit, "the light's position fitted with the formula as written",
     "a search costlier than every variant's fits together", moved_light},
};

// The reading's conclusion: the best reading and those that fit as well, or the closest fit and
// where the frames differ.
FormulaRead concluded(ReadingState& s) {
  if (s.readings.empty()) {
    const model::Fit& closest = closest_fit(s.fit_sets.front(), s.frames, s.o);
    Explanation out;
    out.variant = std::string(model::info(closest.variant).id);
    out.residual = closest.worst_failing;
    out.text = where_they_differ("The grader cannot say why from the homework's formula: no change of one or two of its parts reproduces your "
                                 "frames (the closest leaves " + percent(closest.worst_failing, 1) + " of a frame's pixels off).",
                                 s.regions());
    out.label = "not explained";
    return {out, {}};
  }
  const model::Fit* best = s.readings.front().fit;
  const bool on_placed = s.placed_fits && !s.placed_fits->empty() && best >= s.placed_fits->data() && best < s.placed_fits->data() + s.placed_fits->size();
  return {explained_by(s.readings), on_placed ? s.placed->offsets : std::vector<double>{}};
}

}  // namespace

FormulaRead explain_with_formula(const FormulaEvidence& e, const GradeOptions& options) {
  ReadingState s = start_reading(e, options);
  for (const Stage& stage : kStages) {
    if (!stage.applies(s)) continue;
    if (auto ended = stage.read(s)) return {std::move(*ended), {}};
  }
  return concluded(s);
}

void say_explanation(Report& report) {
  if (!report.explanation || !report.diagnosis.empty()) return;
  auto& m = report.messages;
  m.insert(report.explanation->explained ? m.begin() : m.end(), report.explanation->text);
}

}  // namespace shadelab::grade
