#pragma once
// The geometry the formula (model/lighting.h) is evaluated on, rendered as the reference is: the
// reference's own vertex shader with a fragment shader that writes, to a float target, the
// eye-space position, the normal as interpolated, or the normal as a `flat` varying receives it
// (model/surface.h reads them). Three renders per set of angles, kept with the references (memory,
// disk, Redis) like any reference render: one course's geometry is rendered once.
#include <array>
#include <string>

#include "core/expected.h"
#include "grade/grade_spec.h"
#include "render/render_request.h"

namespace shadelab::grade {

// Whether a vertex shader declares `out vec3 name;` (with or without a precision qualifier).
bool writes_vec3_varying(const std::string& vertex, const std::string& name);

// The position, normal and flat normal renders of `reference` (its size, angles, samples and
// page), or why the reference's vertex shader cannot give them.
Expected<std::array<render::RenderRequest, 3>> geometry_requests(const FormulaSpec& formula, const render::RenderRequest& reference);

}  // namespace shadelab::grade
