#include "grade/checkpoints.h"

#include "core/check.h"
#include "render/presets.h"

namespace shadelab::grade {

namespace {

struct Edit {
  bool vertex;  // which stage
  const char* from;
  const char* to;
};

shader::ShaderFile edited(shader::ShaderFile file, const char* from, const char* to) {
  const auto at = file.text.find(from);
  SHADELAB_CHECK(at != std::string::npos, "a mistake's edit does not apply to its preset");
  file.text.replace(at, std::string(from).size(), to);
  return file;
}

Mistake mistake(const render::Preset& base, std::string id, std::string message, std::vector<Edit> edits) {
  Mistake m{std::move(id), std::move(message), base.vertex, base.fragment};
  for (const auto& e : edits) (e.vertex ? m.vertex : m.fragment) = edited(e.vertex ? m.vertex : m.fragment, e.from, e.to);
  return m;
}

Checkpoint build(const std::string& name) {
  const auto p = *render::find_preset(name);
  Checkpoint c{name, p.vertex, p.fragment, {}};
  const std::string flat = "flat shading: the normal is not interpolated across each triangle (remove `flat` from the varying)";
  if (name == "smooth") {
    c.mistakes.push_back(mistake(p, "flat_shading", flat, {{true, "out vec4 vNormal;", "flat out vec4 vNormal;"},
                                                           {false, "in vec4 vNormal;", "flat in vec4 vNormal;"}}));
  } else if (name == "gouraud") {
    c.mistakes.push_back(mistake(p, "flat_shading", flat, {{true, "out vec4 vColor;", "flat out vec4 vColor;"},
                                                           {false, "in vec4 vColor;", "flat in vec4 vColor;"}}));
  } else {
    c.mistakes.push_back(mistake(p, "flat_shading", flat, {{true, "out vec4 vNormal;", "flat out vec4 vNormal;"},
                                                           {false, "in vec4 vNormal;", "flat in vec4 vNormal;"}}));
    c.mistakes.push_back(mistake(p, "unnormalized_normals",
                                 "normals not normalized: interpolated normals are shorter than 1, so lighting is too dark "
                                 "between vertices (normalize vNormal in the fragment shader)",
                                 {{false, "vec3 N = normalize(vNormal.xyz);", "vec3 N = vNormal.xyz;"}}));
  }
  if (name == "diffuse") {
    c.mistakes.push_back(mistake(p, "missing_diffuse", "only the ambient colour: the diffuse term is missing",
                                 {{false, "max(0.0, dot(N, L))", "0.0"}}));
  }
  if (name == "specular") {
    c.probes.push_back({"back_light", {-6.0f, 4.0f, -20.0f}});
    const auto d = *render::find_preset("diffuse");
    c.mistakes.push_back(Mistake{"missing_specular", "specular highlight missing: the image matches ambient + diffuse only",
                                 d.vertex, d.fragment});
    c.mistakes.push_back(mistake(p, "unguarded_specular",
                                 "specular added where N.L <= 0: highlights appear on the unlit side (add it only if N.L > 0)",
                                 {{false, "if (NdotL > 0.0) {", "if (true) {"}}));
    c.mistakes.push_back(mistake(p, "missing_diffuse", "the diffuse term is missing: only ambient + specular",
                                 {{false, "uDiffuseColor * uLightColor * max(0.0, NdotL)", "vec4(0.0)"}}));
  }
  return c;
}

}  // namespace

std::vector<std::string> checkpoint_names() { return {"smooth", "gouraud", "diffuse", "specular"}; }

std::optional<Checkpoint> find_checkpoint(const std::string& name) {
  for (const auto& n : checkpoint_names())
    if (n == name) return build(name);
  return std::nullopt;
}

Expected<GradeSpec> checkpoint_spec(const std::string& name, const GradeOptions& options) {
  auto checkpoint = find_checkpoint(name);
  if (!checkpoint)
    return make_error(ErrorCode::unknown_preset, "no checkpoint '" + name + "' (checkpoints: smooth, gouraud, diffuse, specular)");
  return GradeSpec{checkpoint->name, checkpoint->vertex, checkpoint->fragment, std::move(checkpoint->mistakes),
                   std::move(checkpoint->probes), options};
}

}  // namespace shadelab::grade
