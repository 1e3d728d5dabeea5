#include "http/api_request.h"

#include <cmath>
#include <regex>
#include <set>

#include "core/client_json.h"
#include "core/hash.h"
#include "http/request_fields.h"
#include "scene/mesh.h"
#include "worker/course_job.h"

namespace shadelab::http {

using nlohmann::json;

namespace {

// A string from a form: JSON literal where it is one ("9", "true", "[1,2]"), else the string.
// A form value over the JSON budget stays the string it was sent as.
json form_value(const std::string& text) {
  auto parsed = parse_client_json(text, "a form field");
  if (parsed && !parsed->is_string()) return std::move(*parsed);
  return text;
}

}  // namespace

namespace {

const std::set<std::string> kApiFields = {"course", "vertex",  "fragment", "vertexName", "fragmentName", "preset",
                                            "mesh",    "fit",      "width",      "height",       "frames",
                                            "degreesPerFrame", "msaa", "uniforms", "prefix",     "output",
                                            "format", "reference", "referenceVertex", "referenceFragment",
                                            "threshold", "maxFailingFraction", "spatialTolerance", "maxScore"};

}  // namespace

bool is_api_field(const std::string& name) { return kApiFields.count(name) > 0; }

// 128 bits of SHA-256: an id is the capability to use an upload, so it must not be craftable.
std::string mesh_id(const std::string& bytes) { return "m" + sha256_hex(bytes).substr(0, 32); }

Expected<RawRequest> from_json_body(const std::string& body) {
  RawRequest raw;
  auto parsed = parse_client_json(body, "the request body");
  if (!parsed) return parsed.take_error();
  raw.fields = std::move(*parsed);
  if (!raw.fields.is_object()) return bad_request("the request body must be a JSON object");
  return raw;
}

RawRequest from_form(const std::multimap<std::string, std::string>& fields, std::map<std::string, UploadedFile> files) {
  RawRequest raw;
  for (const auto& [k, v] : fields) {
    // Shader sources and names stay strings whatever they look like.
    const bool verbatim = k == "vertex" || k == "fragment" || k == "preset" || k == "mesh" || k == "prefix" || k == "course" ||
                          k == "vertexName" || k == "fragmentName" || k == "output" || k == "format" || k == "reference";
    raw.fields[k] = verbatim ? json(v) : form_value(v);
  }
  raw.files = std::move(files);
  return raw;
}

namespace {

// The frames of a checkpoint's reference are named as the checkpoint's (hw2_normals_*), any other
// preset's by its name.
std::string prefix_of(const course::Course& c, const course::Preset& p) {
  for (const auto& checkpoint : c.checkpoints)
    if (checkpoint.reference == p.name) return checkpoint.prefix;
  return p.name;
}

}  // namespace

Expected<shader::ShaderFile> shader_file(const RawRequest& raw, const char* field, std::string name) {
  if (auto it = raw.files.find(field); it != raw.files.end())
    return shader::ShaderFile{it->second.filename.empty() ? std::move(name) : it->second.filename, it->second.content};
  auto text = text_field(raw.fields, field, "");
  if (!text) return text.take_error();
  return shader::ShaderFile{std::move(name), std::move(*text)};
}

Expected<RequestShaders> read_shaders(const RawRequest& raw, const Limits& limits) {
  const json& f = raw.fields;
  auto preset = text_field(f, "preset", "");
  if (!preset) return preset.take_error();
  const auto source = [&](const char* field, const char* name_field) -> Expected<shader::ShaderFile> {
    auto name = text_field(f, name_field, std::string(field) + ".glsl");
    if (!name) return name.take_error();
    return shader_file(raw, field, std::move(*name));
  };
  auto vertex = source("vertex", "vertexName");
  if (!vertex) return vertex.take_error();
  auto fragment = source("fragment", "fragmentName");
  if (!fragment) return fragment.take_error();
  const bool has_sources = !vertex->text.empty() || !fragment->text.empty() || raw.files.count("vertex") ||
                           raw.files.count("fragment") || f.contains("vertex") || f.contains("fragment");
  if (!preset->empty() && has_sources) return bad_request("give either 'preset' or 'vertex' and 'fragment', not both");
  RequestShaders out{std::move(*preset), std::nullopt};
  if (!has_sources) return out;
  for (const auto* s : {&*vertex, &*fragment})
    if (s->text.size() > limits.render.max_source_bytes)
      return make_error(ErrorCode::payload_too_large, "shader '" + s->name + "' is " + std::to_string(s->text.size()) +
                                                          " bytes; the limit is " + std::to_string(limits.render.max_source_bytes));
  out.code = road::ShaderPair{std::move(*vertex), std::move(*fragment)};
  return out;
}

namespace {

// Shaders: uploaded files, inline sources, or a preset of the course (which also names the frames).
Status read_job_shaders(const RawRequest& raw, worker::JobKind kind, const Limits& limits, const course::Course& course, ParsedJob& out) {
  worker::Job& job = out.job;
  auto shaders = read_shaders(raw, limits);
  if (!shaders) return shaders.take_error();
  if (!shaders->preset.empty()) {
    auto found = course.find_preset(shaders->preset);
    if (!found) return found.take_error();
    if (found->alias) out.warnings.push_back(found->alias->note);
    job.request.vertex = found->preset->vertex;
    job.request.fragment = found->preset->fragment;
    job.prefix = prefix_of(course, *found->preset);
    out.preset = found->preset;
    return Ok{};
  }
  if (kind == worker::JobKind::mesh_check) return Ok{};
  if (!shaders->code) return bad_request("give 'vertex' and 'fragment' shader sources, or a 'preset'");
  job.request.vertex = std::move(shaders->code->vertex);
  job.request.fragment = std::move(shaders->code->fragment);
  return Ok{};
}

// Size, frames, rotation, samples and uniform values.
const RequestFields<render::RenderRequest> kRenderFields = {
    field("width", &render::RenderRequest::width),
    field("height", &render::RenderRequest::height),
    field("frames", &render::RenderRequest::frames),
    field("msaa", &render::RenderRequest::msaa),
    field("degreesPerFrame", &render::RenderRequest::degrees_per_frame),
    field("uniforms", &render::RenderRequest::uniforms),
};

// What comes back and how: fit, prefix, output and format.
Status read_output(const json& f, const course::Course& course, worker::Job& job) {
  if (f.contains("fit") && !f["fit"].is_boolean()) return bad_request("'fit' must be true or false");
  if (f.value("fit", false)) {
    auto target = course::fit_bounds(course);
    if (!target) return target.take_error();
    job.fit = *target;
  }
  auto prefix = text_field(f, "prefix", job.prefix);
  if (!prefix) return prefix.take_error();
  static const std::regex safe_prefix("[A-Za-z0-9_-]{1,64}");
  if (!std::regex_match(*prefix, safe_prefix)) return bad_request("'prefix' may hold only letters, digits, '_' and '-' (at most 64)");
  job.prefix = *prefix;
  auto output = text_field(f, "output", "grid");
  if (!output) return output.take_error();
  if (*output != "grid" && *output != "frames" && *output != "json") return bad_request("'output' must be grid, frames or json");
  job.output = *output == "grid" ? worker::Output::grid : *output == "frames" ? worker::Output::frames : worker::Output::json;
  auto format = text_field(f, "format", "png");
  if (!format) return format.take_error();
  if (*format != "png" && *format != "exr") return bad_request("'format' must be png or exr");
  job.format = *format == "png" ? worker::Format::png : worker::Format::exr;
  job.request.pixel_type = job.format == worker::Format::png ? image::PixelType::u8 : image::PixelType::f32;
  return Ok{};
}

// Mesh: a file in this request, one of the course's meshes by name, or an uploaded id (resolved by
// the caller).
Status read_mesh(const RawRequest& raw, const Limits& limits, const course::Course& course, ParsedJob& out) {
  auto upload = uploaded_mesh(raw, limits);
  if (!upload) return upload.take_error();
  if (*upload) {
    out.job.mesh = (*upload)->id;
    out.job.mesh_format = (*upload)->format;
    out.mesh_upload = std::move(*upload);
    return Ok{};
  }
  auto mesh = text_field(raw.fields, "mesh", course.default_mesh);
  if (!mesh) return mesh.take_error();
  if (course.mesh(*mesh)) return worker::attach_course_mesh(course, *mesh, out.job, out.course_mesh_bytes);
  out.job.mesh = *mesh;
  return Ok{};
}

}  // namespace

Expected<std::optional<road::MeshChoice::Upload>> uploaded_mesh(const RawRequest& raw, const Limits& limits) {
  const auto it = raw.files.find("mesh");
  if (it == raw.files.end()) return std::optional<road::MeshChoice::Upload>();
  const UploadedFile& file = it->second;
  if (file.content.size() > limits.max_mesh_bytes)
    return make_error(ErrorCode::payload_too_large, "the mesh file is larger than " + std::to_string(limits.max_mesh_bytes) + " bytes");
  return std::optional(road::MeshChoice::Upload{mesh_id(file.content), scene::mesh_format_of(file.filename), file.content});
}

Expected<const course::Course*> course_of(const RawRequest& raw, const course::CourseSet& courses) {
  auto id = text_field(raw.fields, "course", "");
  if (!id) return id.take_error();
  return courses.named(*id);
}

Expected<ParsedJob> parse_job(const RawRequest& raw, worker::JobKind kind, const Limits& limits, const course::Course& course) {
  ParsedJob out;
  out.job = worker::course_job(course, kind);
  for (const auto& [k, v] : raw.fields.items())
    if (!is_api_field(k)) out.warnings.push_back("field '" + k + "' is not part of the API and was ignored");
  if (auto s = read_job_shaders(raw, kind, limits, course, out); !s) return s.take_error();
  if (auto s = read_fields(raw.fields, kRenderFields, out.job.request); !s) return s.take_error();
  if (auto s = read_output(raw.fields, course, out.job); !s) return s.take_error();
  if (auto s = read_mesh(raw, limits, course, out); !s) return s.take_error();
  if (kind != worker::JobKind::mesh_check) {
    if (auto valid = render::validate(out.job.request, limits.render); !valid) return valid.take_error();
    if (auto sources = render::check_sources(out.job.request, limits.render); !sources) return sources.take_error();
  }
  return out;
}

}  // namespace shadelab::http
