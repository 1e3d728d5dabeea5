#pragma once
// A failing submission's frames read by the checkpoint's formula (model/fit.h): the change to the
// formula, and the colours and exponent, that reproduce them within the rule a correct submission
// meets against the reference, said in the homework's terms with the numbers. Where no change of
// one or two parts reproduces them, it says so and where the frames differ (grade/difference_regions.h):
// an honest "cannot tell why" rather than a confident wrong explanation.
#include <vector>

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
};

Explanation explain_with_formula(const FormulaEvidence& evidence, const GradeOptions& options);

// The course's values of the formula's parameters (the submission's own where it sets them), and
// the lights its frames were drawn under (the page's, then each probe's).
model::Parameters course_parameters(const FormulaSpec& formula, const std::vector<render::UniformSetting>& values);
std::vector<model::Light> formula_lights(const FormulaSpec& formula, const std::vector<render::UniformSetting>& values,
                                         const std::vector<Probe>& probes);

}  // namespace shadelab::grade
