#pragma once
// The least squares of a formula fit (model/fit.h): the colours that best reproduce a sample of
// the student's pixels at a given exponent, and the exponent found by a grid and a golden-section
// search. Internal to model/.
#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "model/fit.h"

namespace shadelab::model {

// A pixel of the sample: which frame, which point, and what the student drew there.
struct Sampled {
  std::size_t frame, point;
  glm::vec3 drawn;
};

// The sample as the least squares see it, for one variant: what each colour multiplies at each
// pixel but the exponent, the specular cosine's logarithm (pow(c, α) = exp(α ln c)), and whether
// each channel takes part (a colour the canvas clamped, or divided by an alpha under 1, tells only
// a bound).
struct Design {
  struct Row {
    glm::vec3 diffuse;     // diffuse light x d
    glm::vec3 specular;    // specular light
    // ln c at each sample the specular term is averaged over; -inf where c = 0 or the term is not added
    std::array<float, kMaxSamples> log_cosine;
    int samples;
    glm::vec3 drawn;
    glm::bvec3 used;
  };
  std::vector<Row> rows;
};

struct Trial {
  Parameters parameters;
  double rms;  // of the least squares, on the pixels they use
};

// The design of `sample` for one variant, whose factors at each sampled pixel are `f`.
Design design_of(const std::vector<Sampled>& sample, const std::vector<Factors>& f, const FitOptions& o);

// The colours that best reproduce the sample at exponent `alpha`, channel by channel, pulled weakly
// towards the course's values.
Trial least_squares(const Design& design, float alpha, const FitOptions& o);

// The exponent that `trial` finds best: the best of a grid from 0.5 to 256 (ratio 2^(1/3)), then
// a golden-section search between its neighbours; the course's own where none is better.
using ExponentTrial = std::function<Trial(float)>;
Trial best_exponent(const ExponentTrial& trial, const FitOptions& o);

// The colours refitted at every exponent tried.
Trial fitted_values(const Design& design, const FitOptions& o);

}  // namespace shadelab::model
