#include "http/grade_request.h"

#include <set>

#include "core/base64.h"
#include "core/client_json.h"
#include "http/request_fields.h"
#include "scene/mesh.h"

namespace shadelab::http {

using nlohmann::json;

namespace {

using road::CodeRequest;
using road::RenderShape;
using road::ToleranceShape;

// What is drawn, what it is graded against, how closely, and the result's format. The shaders and
// the files (the mesh, the page's own reference) are read beside the table: each may be an upload.
const RequestFields<ParsedCodeGrade> kCodeFields = {
    field("format", &ParsedCodeGrade::result_format),
    field("width", &ParsedCodeGrade::request, &CodeRequest::render, &RenderShape::width),
    field("height", &ParsedCodeGrade::request, &CodeRequest::render, &RenderShape::height),
    field("frames", &ParsedCodeGrade::request, &CodeRequest::render, &RenderShape::frames),
    field("msaa", &ParsedCodeGrade::request, &CodeRequest::render, &RenderShape::msaa),
    field("degreesPerFrame", &ParsedCodeGrade::request, &CodeRequest::render, &RenderShape::degrees_per_frame),
    field("uniforms", &ParsedCodeGrade::request, &CodeRequest::render, &RenderShape::uniforms),
    field("fit", &ParsedCodeGrade::request, &CodeRequest::render, &RenderShape::fit),
    field("mesh", &ParsedCodeGrade::request, &CodeRequest::mesh, &road::MeshChoice::name),
    field("reference", &ParsedCodeGrade::request, &CodeRequest::reference),
    field("threshold", &ParsedCodeGrade::request, &CodeRequest::tolerance, &ToleranceShape::threshold),
    field("maxFailingFraction", &ParsedCodeGrade::request, &CodeRequest::tolerance, &ToleranceShape::max_failing_fraction),
    field("maxScore", &ParsedCodeGrade::request, &CodeRequest::tolerance, &ToleranceShape::max_score),
    field("spatialTolerance", &ParsedCodeGrade::request, &CodeRequest::tolerance, &ToleranceShape::spatial_tolerance),
};

// The files a code grade may upload: its mesh (else `mesh` names one) and the page's own reference.
Status read_code_files(const RawRequest& raw, const Limits& limits, CodeRequest& request) {
  auto upload = uploaded_mesh(raw, limits);
  if (!upload) return upload.take_error();
  request.mesh.upload = std::move(*upload);
  if (!raw.files.count("referenceVertex") && !raw.fields.contains("referenceVertex")) return Ok{};
  auto vertex = shader_file(raw, "referenceVertex", "referenceVertex");
  if (!vertex) return vertex.take_error();
  auto fragment = shader_file(raw, "referenceFragment", "referenceFragment");
  if (!fragment) return fragment.take_error();
  request.own_reference = road::ShaderPair{std::move(*vertex), std::move(*fragment)};
  return Ok{};
}

const std::set<std::string> kFramesFields = {"course", "reference", "mesh", "maxScore", "format", "vertex", "fragment",
                                             "vertexName", "fragmentName", "savedFrames"};

struct FramesFields {
  road::FramesRequest request;
  std::string format;
};

const RequestFields<FramesFields> kFramesTable = {
    field("format", &FramesFields::format),
    field("reference", &FramesFields::request, &road::FramesRequest::reference),
    field("mesh", &FramesFields::request, &road::FramesRequest::mesh),
    field("maxScore", &FramesFields::request, &road::FramesRequest::max_score),
};

// The JSON form's frames: [{"name": "hw2_specular_0.png", "png": base64}, ...].
Status json_frames(const json& list, std::vector<road::HandedInFile>& out) {
  if (!list.is_array()) return bad_request("'savedFrames' must be an array of {\"name\", \"png\"} (the PNG in base64)");
  for (const auto& item : list) {
    if (!item.is_object() || !item.contains("name") || !item["name"].is_string() || !item.contains("png") || !item["png"].is_string())
      return bad_request("each of 'savedFrames' must be {\"name\": \"hw2_specular_0.png\", \"png\": \"<base64>\"}; got " + describe_client_value(item));
    auto bytes = base64_decode(item["png"].get<std::string>());
    if (!bytes) return bad_request("'savedFrames' item '" + item["name"].get<std::string>() + "': 'png' is not base64");
    out.push_back({item["name"].get<std::string>(), std::move(*bytes)});
  }
  return Ok{};
}

// A shader beside the frames: an uploaded file, or the field's text named by `<stage>Name`.
Expected<std::optional<shader::ShaderFile>> shader_beside(const RawRequest& raw, const std::string& stage) {
  auto name = text_field(raw.fields, (stage + "Name").c_str(), stage);
  if (!name) return name.take_error();
  auto shader = shader_file(raw, stage.c_str(), name->empty() ? stage : *name);
  if (!shader) return shader.take_error();
  if (shader->text.empty() && !raw.files.count(stage)) return std::optional<shader::ShaderFile>();
  return std::optional(std::move(*shader));
}

// A field's value where it has the fallback's type, else the fallback: what a request that could
// not be read still says about itself.
template <class T>
T lenient_field(const json& fields, const char* name, T fallback) {
  if (!fields.contains(name)) return fallback;
  const json& v = fields[name];
  if constexpr (std::is_same_v<T, std::string>) return v.is_string() ? v.get<std::string>() : fallback;
  else return v.is_number() ? v.get<T>() : fallback;
}

// A code grade with a field that could not be read: the sources, and the labels of its report.
ParsedGrade misread_code_grade(const RawRequest& raw, const Limits& limits, Error unread) {
  road::CodeRequest request;
  request.reference = lenient_field<std::string>(raw.fields, "reference", "");
  request.tolerance.max_score = lenient_field<double>(raw.fields, "maxScore", 1.0);
  if (auto shaders = read_shaders(raw, limits)) request.code = std::move(shaders->code);
  return ParsedGrade{{std::move(request), std::move(unread), {}}, lenient_field<std::string>(raw.fields, "format", "json")};
}

// The code's size and sources are checked where it is graded (road/submission.h): a shader
// that cannot be sent is the code's grade, and the frames are still graded.
Status read_code_beside(const RawRequest& raw, road::FramesRequest& out) {
  auto vertex = shader_beside(raw, "vertex");
  if (!vertex) return vertex.take_error();
  auto fragment = shader_beside(raw, "fragment");
  if (!fragment) return fragment.take_error();
  if (vertex->has_value() != fragment->has_value())
    return bad_request("give both 'vertex' and 'fragment' (the code the frames were made with), or neither (the frames alone)");
  if (vertex->has_value()) out.code = std::pair{std::move(**vertex), std::move(**fragment)};
  return Ok{};
}

}  // namespace

Expected<ParsedCodeGrade> parse_code_grade(const RawRequest& raw, const Limits& limits) {
  ParsedCodeGrade out;
  for (const auto& [k, v] : raw.fields.items())
    if (!is_api_field(k)) out.warnings.push_back("field '" + k + "' is not part of the API and was ignored");
  if (auto s = read_fields(raw.fields, kCodeFields, out); !s) return s.take_error();
  if (out.result_format != "json" && out.result_format != "gradescope") return bad_request("'format' must be json or gradescope");
  auto shaders = read_shaders(raw, limits);
  if (!shaders) return shaders.take_error();
  if (shaders->preset.empty() && !shaders->code) return bad_request("give 'vertex' and 'fragment' shader sources, or a 'preset'");
  out.request.preset = std::move(shaders->preset);
  out.request.code = std::move(shaders->code);
  if (auto s = read_code_files(raw, limits, out.request); !s) return s.take_error();
  return out;
}

bool has_saved_frames(const RawRequest& raw) { return !raw.frames.empty() || raw.fields.contains("savedFrames"); }

Expected<ParsedFramesGrade> parse_frames_grade(const RawRequest& raw) {
  ParsedFramesGrade out;
  for (const auto& [k, v] : raw.fields.items())
    if (!kFramesFields.count(k)) out.warnings.push_back("field '" + k + "' is not used in a grade of saved frames and was ignored");
  FramesFields fields;
  if (auto s = read_fields(raw.fields, kFramesTable, fields); !s) return s.take_error();
  if (!fields.format.empty() && fields.format != "json")
    return bad_request("saved frames are graded as JSON; for Gradescope's results.json of a whole HW2 folder run `shadelab autograde`");
  if (fields.request.max_score.value_or(0) < 0) return bad_request("'maxScore' must be a number, not negative");
  out.request = std::move(fields.request);
  if (auto s = read_code_beside(raw, out.request); !s) return s.take_error();
  for (const auto& f : raw.frames) out.request.files.push_back({f.filename, f.content});
  if (raw.fields.contains("savedFrames"))
    if (auto s = json_frames(raw.fields["savedFrames"], out.request.files); !s) return s.take_error();
  return out;
}

Expected<ParsedGrade> parse_grade(const RawRequest& raw, const Limits& limits) {
  if (has_saved_frames(raw)) {
    auto frames = parse_frames_grade(raw);
    if (!frames) return frames.take_error();
    return ParsedGrade{{std::move(frames->request), std::nullopt, std::move(frames->warnings)}};
  }
  auto code = parse_code_grade(raw, limits);
  if (!code) return misread_code_grade(raw, limits, code.take_error());
  return ParsedGrade{{std::move(code->request), std::nullopt, std::move(code->warnings)}, std::move(code->result_format)};
}

}  // namespace shadelab::http
