#pragma once
// The geometry the formula (model/lighting.h) is evaluated on, rendered as the reference is: a
// vertex shader of the course's with a fragment shader that writes, to a float target, the
// eye-space position, the normal as interpolated, for a lit checkpoint the normal as a `flat`
// varying receives it, and for a normal-colour checkpoint the colour the reference's vertex shader
// computes, interpolated and flat (model/surface.h reads them), and for a specular one, where it
// is asked for, the flat normal sample by sample. A few renders per set of angles, kept with the
// references (memory, disk, Redis) like any reference render: one course's geometry is rendered once.
#include <optional>
#include <string>
#include <vector>

#include "core/expected.h"
#include "grade/grade_spec.h"
#include "model/surface.h"
#include "render/render_request.h"

namespace shadelab::grade {

// The type a vertex shader declares `out TYPE name;` with ("vec3", "vec4"; a precision qualifier
// allowed), if it declares it.
std::optional<std::string> varying_type(const std::string& vertex, const std::string& name);
// Whether it declares `out vec3 name;`.
bool writes_vec3_varying(const std::string& vertex, const std::string& name);

struct GeometryRender {
  render::RenderRequest request;
  model::Quantity quantity;
  int sample = 0;  // a sample's flat normal: which of the pixel's samples
};

// Whether the geometry keeps a specular checkpoint's flat normal sample by sample: a flat-shaded
// highlight is the mean of its samples' shades, which no shade of their averaged normal is. Four
// renders more, loaded only where flat shading could be what the frames show.
enum class SampleGeometry { averaged, each_sample };

// The renders the formula's geometry is read from, the position first (its alpha tells the
// object's pixels), each the size, angles, samples and page of `reference`; or why the course's
// vertex shaders cannot give them. With `each_sample`, a formula with a specular term also gets,
// after those, the flat normal at each of the reference's sample positions (a render without MSAA
// each), where the MSAA pattern is a standard one (render/sample_positions.h).
Expected<std::vector<GeometryRender>> geometry_requests(const FormulaSpec& formula, const render::RenderRequest& reference,
                                                        SampleGeometry samples = SampleGeometry::averaged);
// Whether `each_sample` adds any render for this formula and reference.
bool has_sample_geometry(const FormulaSpec& formula, const render::RenderRequest& reference);

}  // namespace shadelab::grade
