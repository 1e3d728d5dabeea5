#include "grade/formula_geometry.h"

#include <regex>

namespace shadelab::grade {

namespace {

std::regex declaration(const std::string& name) {
  return std::regex("(^|[;\\s])out\\s+((?:highp|mediump|lowp)\\s+)?vec3\\s+" + name + "\\s*;");
}

// A fragment shader that writes `value` of the varying `name` (declared `qualifier in vec3`), with
// alpha 2 where it is drawn: the resolve's alpha is then 1 + the samples' coverage over the clear
// colour's alpha of 1.
shader::ShaderFile writer(const std::string& name, const std::string& qualifier) {
  return {"formula_geometry.frag",
          "#version 300 es\nprecision highp float;\n" + qualifier + "in vec3 " + name + ";\nout vec4 geometry;\n"
          "void main(void) { geometry = vec4(" + name + ", 2.0); }\n"};
}

}  // namespace

bool writes_vec3_varying(const std::string& vertex, const std::string& name) {
  return std::regex_search(vertex, declaration(name));
}

Expected<std::array<render::RenderRequest, 3>> geometry_requests(const FormulaSpec& formula, const render::RenderRequest& reference) {
  const std::string& text = reference.vertex.text;
  if (!writes_vec3_varying(text, formula.position_varying) || !writes_vec3_varying(text, formula.normal_varying))
    return make_error(ErrorCode::invalid_argument, "the reference's vertex shader does not write " + formula.position_varying + " and " +
                                                       formula.normal_varying + " as vec3 varyings");
  render::RenderRequest base = reference;
  base.pixel_type = image::PixelType::f32;
  base.semantics = render::FloatSemantics::as_compiled;
  base.uniforms.clear();  // the geometry reads no colour, and one key serves every submission's values
  std::array<render::RenderRequest, 3> out = {base, base, base};
  out[0].fragment = writer(formula.position_varying, "");
  out[1].fragment = writer(formula.normal_varying, "");
  out[2].vertex.text = std::regex_replace(text, declaration(formula.normal_varying), "$1flat out $2vec3 " + formula.normal_varying + ";",
                                          std::regex_constants::format_first_only);
  out[2].fragment = writer(formula.normal_varying, "flat ");
  return out;
}

}  // namespace shadelab::grade
