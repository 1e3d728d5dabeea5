#include "http/request_reader.h"

#include "core/client_json.h"

namespace shadelab::http {

using nlohmann::json;

Expected<RawRequest> read_request(const httplib::Request& req) {
  if (req.is_multipart_form_data()) {
    std::multimap<std::string, std::string> fields;
    std::map<std::string, UploadedFile> files;
    std::vector<UploadedFile> frames;  // a part name that repeats: one per saved frame
    for (const auto& [name, part] : req.files) {
      if (part.filename.empty()) fields.emplace(name, part.content);
      else if (name == "frames") frames.push_back({part.filename, part.content});
      else files[name] = {part.filename, part.content};
    }
    RawRequest raw = from_form(fields, std::move(files));
    raw.frames = std::move(frames);
    return raw;
  }
  if (req.method == "GET") return from_form(req.params, {});
  const std::string type = req.get_header_value("Content-Type");
  if (type.rfind("application/x-www-form-urlencoded", 0) == 0) return from_form(req.params, {});
  if (!type.empty() && type.find("json") == std::string::npos)
    return make_error(ErrorCode::invalid_argument, "send JSON (Content-Type: application/json) or multipart/form-data; got " + type);
  return from_json_body(req.body);
}

Expected<SceneUpload> read_scene(const httplib::Request& req) {
  auto raw = read_request(req);
  if (!raw) return raw.take_error();
  if (!req.is_multipart_form_data()) return SceneUpload{std::move(raw->fields), {}};
  SceneUpload upload{nullptr, std::move(raw->files)};
  if (auto part = upload.files.find("scene"); part != upload.files.end()) {
    auto scene = parse_client_json(part->second.content, "the scene");
    if (!scene) return scene.take_error();
    upload.scene = std::move(*scene);
    upload.files.erase(part);
  } else if (raw->fields.contains("scene")) {
    upload.scene = raw->fields["scene"];  // a text part, already parsed as JSON where it is JSON
  } else {
    return make_error(ErrorCode::invalid_argument, "send the scene JSON in the multipart part 'scene'");
  }
  if (upload.scene.is_discarded() || upload.scene.is_string()) return make_error(ErrorCode::invalid_argument, "the scene is not valid JSON");
  return upload;
}

}  // namespace shadelab::http
