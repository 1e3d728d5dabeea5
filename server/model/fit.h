#pragma once
// Which variant of the formula (model/lighting.h), with which colours and exponent, reproduces the
// frames a student drew: the colours by least squares (the image is linear in them away from the
// clamp), the exponent by a search on one number, each variant on a sample of the pixels, then the
// fit confirmed on every interior pixel with the rule a correct submission meets against the
// reference (a frame fails past `max_failing` of its pixels off by more than `threshold`).
#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "image/image.h"
#include "model/lighting.h"
#include "model/surface.h"

namespace shadelab::model {

struct Colours {
  glm::vec3 ambient{0}, diffuse{0}, specular{0};
  // Their alphas (ambient, diffuse, specular): the course's, never fitted. The canvas divides a
  // pixel's colour by its alpha where that is under 1 (a diffuse term left negative).
  glm::vec3 alpha{1};
};

struct Parameters {
  Colours colours;
  float exponent = 1;  // α; unused by a lambert checkpoint
  // Where the light acts as if it were under every frame (a position written into the shader does
  // not follow the page's, nor a probe's); none: each frame's own.
  std::optional<glm::vec3> light_position;
};

// One frame the student drew, with the geometry and the light it was drawn under.
struct DrawnFrame {
  const FrameSurface* surface = nullptr;
  const image::Image* drawn = nullptr;  // RGBA8, the surface's size
  Light light;
  // The share of its interior pixels a fit may draw off: the rule's, plus what the formula itself
  // draws off of the reference's frame at this angle and light (the model shades each pixel once,
  // from geometry averaged over its samples, where the rasteriser shades each triangle in it; only
  // flat normals are shaded sample by sample).
  double allowed = 0.01;
};

struct FitOptions {
  Terms terms = Terms::phong;
  Parameters course;              // the values the fit starts from and keeps where the frames do not tell
  double threshold = 0.016;       // as image::CompareOptions
  std::size_t sample = 4096;      // pixels each variant is tried on before the full check
  // As image::CompareOptions: a pixel the model draws off still matches where the model's colour
  // at a pixel within one of it is close (frames from another rasteriser: a student's saved frames).
  bool spatial_tolerance = false;
  // One variant alone, where the others are settled (flat normals, on each sample's geometry).
  std::optional<Variant> only;
};

struct Fit {
  Variant variant = Variant::formula;
  Parameters parameters;
  double rms = 0;            // on the sample, in [0, 1] colour units
  double sample_failing = 1; // the sample's share of pixels off by more than the threshold
  // Until check_pixels, the sample's share and false; then the worst frame's share of interior
  // pixels off and whether every frame is within what it allows.
  double worst_failing = 1;
  bool reproduces = false;
  bool course_values = false;  // the course's own values, not the fitted ones
  float specular_peak = 0;   // the largest specular factor on the sample: 0 where no highlight is in view
};

// Every variant the checkpoint's terms allow, fitted on the sample alone: the course's own values
// first where the sample finds them close (a variant that reproduces the frames with them keeps
// them: the fitted values are then what the clamp and the 8 bits blur, not what the student
// changed), then (Phong, where the fitted values come close on the sample and another exponent
// draws it closer with the course's colours) those colours at that exponent, then every value
// fitted; variant after variant, as variants() lists them. None checked.
std::vector<Fit> sample_fits(const std::vector<DrawnFrame>& frames, const FitOptions& options);

// Whether a fit's sample is close enough to be worth a check of every pixel (kSampleMargin).
bool worth_checking(const Fit& fit, const std::vector<DrawnFrame>& frames);

// The fit checked on every interior pixel of every frame, or (`until_off`) up to the first frame
// off: a check that fails costs a frame, not all of them, and its worst share is then a bound.
enum class Extent { whole, until_off };
void check_pixels(Fit& fit, const std::vector<DrawnFrame>& frames, const FitOptions& options, Extent extent);

// Every variant, checked: the course's values where they reproduce, else the fitted ones; best
// first (reproducing ones first, then by rms), the closest checked whole where none reproduces.
// What a test wants; an explanation checks only the fits that could be its reading
// (grade/formula_explanation.cpp).
std::vector<Fit> fit_variants(const std::vector<DrawnFrame>& frames, const FitOptions& options);

// The formula with the light at one fitted position under every frame (the colours fitted with it,
// the exponent the course's): a search from the course's light and from six points around the mesh
// at its distance. For frames no variant reproduces: it costs a few hundred evaluations of the
// sample.
Fit fit_light_position(const std::vector<DrawnFrame>& frames, const FitOptions& options);

// The share of `frame`'s interior pixels that `variant` with `parameters` draws off by more than
// the threshold.
double failing_share(Variant variant, const Parameters& parameters, const DrawnFrame& frame, const FitOptions& options);

// The sum over `frame`'s interior pixels of the squared difference, over the three channels, of
// what `variant` with `parameters` draws (as the canvas stores it) and what the student drew: a
// measure that moves by every pixel's share, where failing_share moves only past the threshold.
double squared_error(Variant variant, const Parameters& parameters, const DrawnFrame& frame, const FitOptions& options);

// A colour and alpha as the canvas stores them: clamped to 8 bits, then (as
// image/canvas_readback.h) the colour divided by an alpha under 1.
glm::vec3 as_canvas_stores(const glm::vec4& colour);

// What `variant` with `parameters` draws at `point` (the colour and alpha before the canvas clamps them).
// `samples` as model::factors takes them.
glm::vec4 shade(Variant variant, const Parameters& parameters, Terms terms, const SurfacePoint& point, const Light& light,
                std::span<const glm::vec3> samples = {});

}  // namespace shadelab::model
