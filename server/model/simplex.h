#pragma once
// Nelder and Mead's simplex search for a minimum of a function of three numbers: what finds a
// light written into a student's shader (model/fit.h's fit_light_position), where the fit has no
// derivative to follow.
#include <functional>

#include <glm/vec3.hpp>

namespace shadelab::model {

// The point the search ends at, from `start` with first steps of `step` along each axis, after
// `iterations` moves of the simplex.
glm::vec3 nelder_mead(const std::function<double(const glm::vec3&)>& f, const glm::vec3& start, float step, int iterations);

}  // namespace shadelab::model
