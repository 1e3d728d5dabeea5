#include "http/frames_request.h"

#include <set>

#include "core/base64.h"
#include "http/request_fields.h"

namespace shadelab::http {

using nlohmann::json;

namespace {

const std::set<std::string> kFramesFields = {"course", "reference", "mesh", "maxScore", "format", "vertex", "fragment",
                                             "vertexName", "fragmentName", "savedFrames"};

// The JSON form's frames: [{"name": "hw2_specular_0.png", "png": base64}, ...].
Expected<std::vector<UploadedFile>> json_frames(const json& fields) {
  const json& list = fields["savedFrames"];
  if (!list.is_array()) return bad_request("'savedFrames' must be an array of {\"name\", \"png\"} (the PNG in base64)");
  std::vector<UploadedFile> out;
  for (const auto& item : list) {
    if (!item.is_object() || !item.contains("name") || !item["name"].is_string() || !item.contains("png") || !item["png"].is_string())
      return bad_request("each of 'savedFrames' must be {\"name\": \"hw2_specular_0.png\", \"png\": \"<base64>\"}; got " + item.dump().substr(0, 80));
    auto bytes = base64_decode(item["png"].get<std::string>());
    if (!bytes) return bad_request("'savedFrames' item '" + item["name"].get<std::string>() + "': 'png' is not base64");
    out.push_back({item["name"].get<std::string>(), std::move(*bytes)});
  }
  return out;
}

// A shader beside the frames: an uploaded file, or the field's text named by `<stage>Name`.
Expected<std::optional<shader::ShaderFile>> shader_of(const RawRequest& raw, const std::string& stage) {
  if (auto it = raw.files.find(stage); it != raw.files.end()) return std::optional(shader::ShaderFile{it->second.filename, it->second.content});
  auto source = text_field(raw.fields, stage.c_str(), "");
  if (!source) return source.take_error();
  if (source->empty()) return std::optional<shader::ShaderFile>();
  auto name = text_field(raw.fields, (stage + "Name").c_str(), "");
  if (!name) return name.take_error();
  return std::optional(shader::ShaderFile{name->empty() ? stage : *name, std::move(*source)});
}

// The code's size and sources are checked where it is graded (road/submission.h): a shader
// that cannot be sent is the code's grade, and the frames are still graded.
Status read_code(const RawRequest& raw, road::FramesRequest& out) {
  auto vertex = shader_of(raw, "vertex");
  if (!vertex) return vertex.take_error();
  auto fragment = shader_of(raw, "fragment");
  if (!fragment) return fragment.take_error();
  if (vertex->has_value() != fragment->has_value())
    return bad_request("give both 'vertex' and 'fragment' (the code the frames were made with), or neither (the frames alone)");
  if (!vertex->has_value()) return Ok{};
  out.code = std::pair{std::move(**vertex), std::move(**fragment)};
  return Ok{};
}

}  // namespace

bool has_saved_frames(const RawRequest& raw) { return !raw.frames.empty() || raw.fields.contains("savedFrames"); }

Expected<ParsedFramesGrade> parse_frames_grade(const RawRequest& raw) {
  ParsedFramesGrade out;
  for (const auto& [k, v] : raw.fields.items())
    if (!kFramesFields.count(k)) out.warnings.push_back("field '" + k + "' is not used in a grade of saved frames and was ignored");
  auto format = text_field(raw.fields, "format", "");
  if (!format) return format.take_error();
  if (!format->empty() && *format != "json")
    return bad_request("saved frames are graded as JSON; for Gradescope's results.json of a whole HW2 folder run `shadelab autograde`");
  auto reference = text_field(raw.fields, "reference", "");
  if (!reference) return reference.take_error();
  out.request.reference = *reference;
  auto mesh = text_field(raw.fields, "mesh", "");
  if (!mesh) return mesh.take_error();
  out.request.mesh = *mesh;
  if (raw.fields.contains("maxScore")) {
    if (!raw.fields["maxScore"].is_number() || raw.fields["maxScore"].get<double>() < 0) return bad_request("'maxScore' must be a number, not negative");
    out.request.max_score = raw.fields["maxScore"].get<double>();
  }
  if (auto s = read_code(raw, out.request); !s) return s.take_error();
  for (const auto& f : raw.frames) out.request.files.push_back({f.filename, f.content});
  if (raw.fields.contains("savedFrames")) {
    auto listed = json_frames(raw.fields);
    if (!listed) return listed.take_error();
    for (auto& f : *listed) out.request.files.push_back({std::move(f.filename), std::move(f.content)});
  }
  return out;
}

}  // namespace shadelab::http
