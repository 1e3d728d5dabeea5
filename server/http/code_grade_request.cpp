#include "http/code_grade_request.h"

#include "http/request_fields.h"
#include "scene/mesh.h"

namespace shadelab::http {

using nlohmann::json;

namespace {

Expected<std::optional<int>> optional_integer(const json& f, const char* name) {
  if (!f.contains(name)) return std::optional<int>();
  auto v = integer_field(f, name, 0);
  if (!v) return v.take_error();
  return std::optional(*v);
}

Expected<std::optional<double>> optional_number(const json& f, const char* name) {
  if (!f.contains(name)) return std::optional<double>();
  auto v = number_field(f, name, 0);
  if (!v) return v.take_error();
  return std::optional(*v);
}

Status read_render_shape(const json& f, road::RenderShape& shape) {
  for (auto [name, to] : {std::pair{"width", &shape.width}, {"height", &shape.height}, {"frames", &shape.frames}, {"msaa", &shape.msaa}}) {
    auto v = optional_integer(f, name);
    if (!v) return v.take_error();
    *to = *v;
  }
  auto degrees = optional_number(f, "degreesPerFrame");
  if (!degrees) return degrees.take_error();
  shape.degrees_per_frame = *degrees;
  auto uniforms = read_uniforms(f);
  if (!uniforms) return uniforms.take_error();
  shape.uniforms = std::move(*uniforms);
  if (f.contains("fit") && !f["fit"].is_boolean()) return bad_request("'fit' must be true or false");
  shape.fit = f.value("fit", false);
  return Ok{};
}

// A mesh file in this request, or a name: one of the course's meshes, or an uploaded id.
Status read_mesh(const RawRequest& raw, const Limits& limits, ParsedCodeGrade& out) {
  auto upload = uploaded_mesh(raw, limits);
  if (!upload) return upload.take_error();
  if (const UploadedFile* file = *upload) {
    out.request.mesh.upload = {mesh_id(file->content), scene::mesh_format_of(file->filename), file->content};
    return Ok{};
  }
  auto mesh = text_field(raw.fields, "mesh", "");
  if (!mesh) return mesh.take_error();
  out.request.mesh.name = *mesh;
  return Ok{};
}

// The page's own reference: uploaded files or inline sources, named by their fields.
Expected<road::ShaderPair> own_reference(const RawRequest& raw) {
  const auto source = [&](const char* field) -> Expected<shader::ShaderFile> {
    if (auto it = raw.files.find(field); it != raw.files.end()) return shader::ShaderFile{it->second.filename, it->second.content};
    auto t = text_field(raw.fields, field, "");
    if (!t) return t.take_error();
    return shader::ShaderFile{field, *t};
  };
  auto vertex = source("referenceVertex");
  if (!vertex) return vertex.take_error();
  auto fragment = source("referenceFragment");
  if (!fragment) return fragment.take_error();
  return road::ShaderPair{std::move(*vertex), std::move(*fragment)};
}

Status read_against(const RawRequest& raw, road::CodeRequest& request) {
  auto reference = text_field(raw.fields, "reference", "");
  if (!reference) return reference.take_error();
  request.reference = *reference;
  if (!raw.files.count("referenceVertex") && !raw.fields.contains("referenceVertex")) return Ok{};
  auto own = own_reference(raw);
  if (!own) return own.take_error();
  request.own_reference = std::move(*own);
  return Ok{};
}

Status read_tolerance(const json& f, road::ToleranceShape& t) {
  for (auto [name, to] : {std::pair{"threshold", &t.threshold}, {"maxFailingFraction", &t.max_failing_fraction}, {"maxScore", &t.max_score}}) {
    auto v = optional_number(f, name);
    if (!v) return v.take_error();
    *to = *v;
  }
  if (f.contains("spatialTolerance") && !f["spatialTolerance"].is_boolean()) return bad_request("'spatialTolerance' must be true or false");
  t.spatial_tolerance = f.value("spatialTolerance", false);
  return Ok{};
}

}  // namespace

Expected<ParsedCodeGrade> parse_code_grade(const RawRequest& raw, const Limits& limits) {
  ParsedCodeGrade out;
  for (const auto& [k, v] : raw.fields.items())
    if (!is_api_field(k)) out.warnings.push_back("field '" + k + "' is not part of the API and was ignored");
  auto format = text_field(raw.fields, "format", "json");
  if (!format) return format.take_error();
  if (*format != "json" && *format != "gradescope") return bad_request("'format' must be json or gradescope");
  out.result_format = *format;
  auto shaders = read_shaders(raw, limits);
  if (!shaders) return shaders.take_error();
  if (shaders->preset.empty() && !shaders->code) return bad_request("give 'vertex' and 'fragment' shader sources, or a 'preset'");
  out.request.preset = std::move(shaders->preset);
  out.request.code = std::move(shaders->code);
  if (auto s = read_render_shape(raw.fields, out.request.render); !s) return s.take_error();
  if (auto s = read_mesh(raw, limits, out); !s) return s.take_error();
  if (auto s = read_against(raw, out.request); !s) return s.take_error();
  if (auto s = read_tolerance(raw.fields, out.request.tolerance); !s) return s.take_error();
  return out;
}

}  // namespace shadelab::http
