#pragma once
// The formula's fits said in the homework's words (grade/formula_explanation.h's readings): what a
// fit changes, counted, in sentences and labels with the numbers; the order readings are offered
// in; which of them reproduce the frames. Shared by the reading's stages and the catalogue's
// recognition (grade/catalogue_reading.h); not for callers outside grade/.
#include <array>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "grade/grade_spec.h"
#include "grade/report.h"
#include "model/fit.h"
#include "render/uniform_plan.h"

namespace shadelab::grade {

// A colour the frames show as different: some channel off by more than 5/255. An exponent: more
// than 5% off (the fit finds the course's 6.0 to within 1% on its own reference).
inline constexpr float kColourTolerance = 0.02f;
inline constexpr double kExponentTolerance = 0.05;
// A reading's light position: 5% of each coordinate, as the fit finds a moved light.
inline constexpr double kPositionTolerance = 0.05;
// Explanations whose residual is within this factor of the best one's fit as well.
inline constexpr double kAsWell = 1.25;
// The most changes an explanation may make: a student's slip is one or two.
inline constexpr int kMostChanges = 2;

// The submission's value of a formula input (its own where it sets one, else the course's).
std::array<float, 3> value_of(const FormulaInput& in, const std::vector<render::UniformSetting>& values);
float alpha_of(const FormulaInput& in, const std::vector<render::UniformSetting>& values);
glm::vec3 as_vec3(const std::array<float, 3>& a);

std::string number_text(double v, const char* format = "%.2f");
std::string triple(const glm::vec3& c);  // "(0.40, 0.20, 0.20)"
bool colours_near(const glm::vec3& a, const glm::vec3& b);  // within kColourTolerance, channel by channel

// What an explanation changes, counted and said.
struct Reading {
  model::Fit* fit = nullptr;  // checked on every pixel in place (reproducing_readings)
  std::vector<Explanation::Parameter> parameters;
  std::vector<std::string> changes;  // a sentence each
  std::vector<std::string> labels;   // a few words each
  int count = 0;
};

// A fit said: each change it makes to the formula, with the course's value and the fitted one.
Reading reading_of(model::Fit& fit, const model::Parameters& course, const model::Light& page, const FormulaSpec& f);

// The order explanations are offered in: the fewest changes first; of as many, values changed
// before the formula's structure (frames with no highlight in view fit "the specular term is
// missing" and a view vector that points away alike: the missing term is the likelier slip, and
// both are said), a variant's course values before its fitted ones; then the closest.
bool before(const Reading& a, const Reading& b);

// Whether a reading is said beside the best one: as many changes, and as close (kAsWell).
bool as_well(const Reading& r, const Reading& best);

// The readings that reproduce the frames: the best, then those that fit as well. Each fit is
// checked on every pixel only when it could still be one of them, in the order they are offered:
// a check is the explanation's cost (a frame's every pixel, each frame), and frames with the
// specular term missing are reproduced by every change to the specular's direction alike. A
// variant is settled by its first fit that reproduces (its course values, where they do): a
// variant with no change (the formula with the course's values) is no reading.
std::vector<Reading> reproducing_readings(std::vector<model::Fit>& candidates, const std::vector<model::DrawnFrame>& frames,
                                          const model::FitOptions& o, const model::Light& page, const FormulaSpec& f);

// The fit a student is told is closest where no reading reproduces the frames, checked whole:
// one that reproduces with too many changes (or none), else the fitted values closest on the sample.
const model::Fit& closest_fit(std::vector<model::Fit>& candidates, const std::vector<model::DrawnFrame>& frames, const model::FitOptions& o);

}  // namespace shadelab::grade
