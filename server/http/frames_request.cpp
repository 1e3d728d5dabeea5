#include "http/frames_request.h"

#include <filesystem>
#include <set>

#include "core/base64.h"
#include "core/words.h"
#include "course/submission_files.h"
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
Status read_code(const RawRequest& raw, road::FramesSubmission& out) {
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

// The frames in the deliverable's order, those not handed in, and warnings for the rest.
void order_frames(const course::Course& course, const course::Checkpoint& checkpoint, std::vector<UploadedFile> files, ParsedFramesGrade& out) {
  std::vector<std::filesystem::path> names;
  for (const auto& f : files) names.emplace_back(std::filesystem::path(f.filename).filename());
  const auto found = course::saved_frame_files(course, checkpoint, names);
  out.submission.missing = found.missing(course, checkpoint);
  std::set<std::string> used;
  for (const auto& frame : found.frames) {
    if (!frame) continue;
    for (auto& f : files)
      if (std::filesystem::path(f.filename).filename() == *frame && used.insert(frame->string()).second) {
        out.submission.saved.push_back({frame->string(), std::move(f.content)});
        break;
      }
  }
  for (const auto& n : names)
    if (!used.count(n.string()))
      out.warnings.push_back(n.string() + " is not one of the " + checkpoint.name + " deliverable's frames (" +
                             course.frame_file(checkpoint.prefix, 0, "png") + " to " +
                             course.frame_file(checkpoint.prefix, course.frames - 1, "png") + ") and was not graded");
}

}  // namespace

bool has_saved_frames(const RawRequest& raw) { return !raw.frames.empty() || raw.fields.contains("savedFrames"); }

Expected<ParsedFramesGrade> parse_frames_grade(const RawRequest& raw, const course::Course& course) {
  ParsedFramesGrade out;
  for (const auto& [k, v] : raw.fields.items())
    if (!kFramesFields.count(k)) out.warnings.push_back("field '" + k + "' is not used in a grade of saved frames and was ignored");
  auto format = text_field(raw.fields, "format", "");
  if (!format) return format.take_error();
  if (!format->empty() && *format != "json")
    return bad_request("saved frames are graded as JSON; for Gradescope's results.json of a whole HW2 folder run `shadelab autograde`");
  auto reference = text_field(raw.fields, "reference", "");
  if (!reference) return reference.take_error();
  if (reference->empty()) return bad_request("give 'reference': the deliverable the frames are of (" + and_list(course.checkpoint_names()) + ")");
  auto found = course.checkpoint(*reference);
  if (!found) return found.take_error();
  if (found->alias) out.warnings.push_back(found->alias->note);
  out.checkpoint = found->checkpoint;
  auto mesh = text_field(raw.fields, "mesh", "");
  if (!mesh) return mesh.take_error();
  out.settings.mesh = *mesh;
  out.settings.max_score = found->checkpoint->points;
  if (raw.fields.contains("maxScore")) {
    if (!raw.fields["maxScore"].is_number() || raw.fields["maxScore"].get<double>() < 0) return bad_request("'maxScore' must be a number, not negative");
    out.settings.max_score = raw.fields["maxScore"].get<double>();
  }
  if (auto s = read_code(raw, out.submission); !s) return s.take_error();
  std::vector<UploadedFile> files = raw.frames;
  if (raw.fields.contains("savedFrames")) {
    auto listed = json_frames(raw.fields);
    if (!listed) return listed.take_error();
    files.insert(files.end(), listed->begin(), listed->end());
  }
  order_frames(course, *found->checkpoint, std::move(files), out);
  return out;
}

}  // namespace shadelab::http
