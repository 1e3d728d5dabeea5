#pragma once
// A failing submission's frames read by the checkpoint's formula (model/fit.h): the change to the
// formula, and the colours and exponent, that reproduce them within the rule a correct submission
// meets against the reference, said in the homework's terms with the numbers. Where no change of
// one or two parts reproduces them, it says so and where the frames differ (grade/difference_regions.h):
// an honest "cannot tell why" rather than a confident wrong explanation. The reading runs as an
// ordered table of stages (formula_explanation.cpp); the kinds of explanation (the formula's
// variants, the course's catalogue, the grader's own diagnoses) and where a new mistake belongs are
// written down once, in docs/grading.md ("The kinds of explanation").
#include <functional>
#include <vector>

#include "grade/edge_placement.h"
#include "grade/grade_spec.h"
#include "grade/report.h"
#include "model/fit.h"
#include "model/surface.h"
#include "render/uniform_plan.h"

namespace shadelab::grade {

struct FormulaEvidence {
  const FormulaSpec* formula = nullptr;
  std::vector<render::UniformSetting> values;  // the submission's uniform values (over the course's)
  std::vector<Probe> probes;                   // the lights after the page's, in the frames' order
  const std::vector<model::FrameSurface>* surfaces = nullptr;  // one per angle
  const SharedFrames* student = nullptr;       // every light's frames, light after light
  const SharedFrames* reference = nullptr;     // the same, the reference's
  // The same geometry with each sample's flat normal (grade/formula_geometry.h), fetched only where
  // no one change explains the frames on `surfaces`: flat shading's highlights are read on it. None
  // where the formula has no such geometry.
  std::function<const std::vector<model::FrameSurface>*()> sampled;
  // Saved frames only: the flat colour drawn again at angles moved from the outlines' fit, which
  // misses a flat colour's edges by more than the rule allows (grade/edge_placement.h). Called only
  // where the flat colour is close and does not reproduce the frames; none for code, drawn at exact angles.
  MovedFlatColour moved_flat_colour;
};

// What the formula read, and where: each angle's move in degrees where the reading is of frames
// placed by their edges (grade/edge_placement.h), empty where it is of the angles given.
struct FormulaRead {
  Explanation explanation;
  std::vector<double> angle_moves;
};
FormulaRead explain_with_formula(const FormulaEvidence& evidence, const GradeOptions& options);

// The report's explanation among its messages, for the student (the page, Gradescope, the CLI):
// first when it explains, last (after what the probes say) when it cannot. Where a catalogued
// mistake or a changed starter constant has said what went wrong, its words stay the student's and
// the explanation is in the JSON only.
void say_explanation(Report& report);

// The course's values of the formula's parameters (the submission's own where it sets them), and
// the lights its frames were drawn under (the page's, then each probe's).
model::Parameters course_parameters(const FormulaSpec& formula, const std::vector<render::UniformSetting>& values);
std::vector<model::Light> formula_lights(const FormulaSpec& formula, const std::vector<render::UniformSetting>& values,
                                         const std::vector<Probe>& probes);

}  // namespace shadelab::grade
