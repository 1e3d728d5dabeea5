#include "grade/formula_geometry.h"

#include <regex>

#include "render/sample_positions.h"

namespace shadelab::grade {

namespace {

std::regex declaration(const std::string& name, const std::string& type) {
  return std::regex("(^|[;\\s])out\\s+((?:highp|mediump|lowp)\\s+)?(" + type + ")\\s+" + name + "\\s*;");
}

// A fragment shader that writes `value` of the varying `name` (declared `qualifier in type`), with
// alpha 2 where it is drawn: the resolve's alpha is then 1 + the samples' coverage over the clear
// colour's alpha of 1.
shader::ShaderFile writer(const std::string& name, const std::string& type, const std::string& qualifier) {
  const std::string value = type == "vec3" ? name : name + ".rgb";
  return {"formula_geometry.frag",
          "#version 300 es\nprecision highp float;\n" + qualifier + "in " + type + " " + name + ";\nout vec4 geometry;\n"
          "void main(void) { geometry = vec4(" + value + ", 2.0); }\n"};
}

render::RenderRequest writing(const render::RenderRequest& base, const std::string& vertex, const std::string& name, const std::string& type) {
  render::RenderRequest out = base;
  out.vertex.text = vertex;
  out.fragment = writer(name, type, "");
  return out;
}

// The same, with the varying `flat`: the provoking vertex's value across each triangle.
render::RenderRequest as_flat(const render::RenderRequest& base, const std::string& vertex, const std::string& name, const std::string& type) {
  render::RenderRequest out = base;
  out.vertex.text = std::regex_replace(vertex, declaration(name, type), "$1flat out $2$3 " + name + ";", std::regex_constants::format_first_only);
  out.fragment = writer(name, type, "flat ");
  return out;
}

}  // namespace

std::optional<std::string> varying_type(const std::string& vertex, const std::string& name) {
  std::smatch m;
  if (!std::regex_search(vertex, m, declaration(name, "vec3|vec4"))) return std::nullopt;
  return m[3].str();
}

bool writes_vec3_varying(const std::string& vertex, const std::string& name) { return varying_type(vertex, name) == "vec3"; }

bool has_sample_geometry(const FormulaSpec& formula, const render::RenderRequest& reference) {
  return formula.terms == model::Terms::phong && !render::standard_sample_positions(reference.msaa).empty();
}

Expected<std::vector<GeometryRender>> geometry_requests(const FormulaSpec& formula, const render::RenderRequest& reference, SampleGeometry samples) {
  const std::string& text = formula.geometry_vertex.text.empty() ? reference.vertex.text : formula.geometry_vertex.text;
  if (!writes_vec3_varying(text, formula.position_varying) || !writes_vec3_varying(text, formula.normal_varying))
    return make_error(ErrorCode::invalid_argument,
                      "the formula's vertex shader does not write " + formula.position_varying + " and " + formula.normal_varying + " as vec3 varyings");
  render::RenderRequest base = reference;
  base.pixel_type = image::PixelType::f32;
  base.semantics = render::FloatSemantics::as_compiled;
  base.uniforms.clear();  // the geometry reads no colour, and one key serves every submission's values
  std::vector<GeometryRender> out = {{writing(base, text, formula.position_varying, "vec3"), model::Quantity::position},
                                     {writing(base, text, formula.normal_varying, "vec3"), model::Quantity::normal}};
  // The normal's colour reads no flat normal: its flat variant is the flat colour's own render.
  if (formula.terms != model::Terms::normal_colour) out.push_back({as_flat(base, text, formula.normal_varying, "vec3"), model::Quantity::flat_normal});
  if (samples == SampleGeometry::each_sample && has_sample_geometry(formula, reference)) {
    const auto positions = render::standard_sample_positions(reference.msaa);
    for (std::size_t i = 0; i < positions.size() && i < static_cast<std::size_t>(model::kMaxSamples); ++i) {
      render::RenderRequest one = base;
      one.msaa = 0;
      one.sample_position = positions[i];
      out.push_back({as_flat(one, text, formula.normal_varying, "vec3"), model::Quantity::sample_flat_normal, static_cast<int>(i)});
    }
  }
  if (formula.terms == model::Terms::normal_colour) {
    const auto type = varying_type(reference.vertex.text, formula.colour_varying);
    if (!type) return make_error(ErrorCode::invalid_argument, "the reference's vertex shader does not write " + formula.colour_varying + " as a vec3 or vec4 varying");
    out.push_back({writing(base, reference.vertex.text, formula.colour_varying, *type), model::Quantity::colour});
    out.push_back({as_flat(base, reference.vertex.text, formula.colour_varying, *type), model::Quantity::flat_colour});
  }
  return out;
}

}  // namespace shadelab::grade
