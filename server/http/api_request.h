#pragma once
// Turns what a client sent (a JSON body, multipart/form-data, or a GET query) into a validated
// worker job. Every field is type-checked here; nothing invalid reaches a worker.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "course/course_set.h"
#include "http/limits.h"
#include "road/code_request.h"
#include "worker/job.h"

namespace shadelab::http {

// A request in neutral form: field name -> JSON value, plus uploaded files.
struct UploadedFile {
  std::string filename;
  std::string content;
};
struct RawRequest {
  nlohmann::json fields = nlohmann::json::object();
  std::map<std::string, UploadedFile> files;  // "vertex", "fragment", "mesh"
  std::vector<UploadedFile> frames;           // multipart parts named "frames", in the order sent
};

struct ParsedJob {
  worker::Job job;
  std::optional<road::MeshChoice::Upload> mesh_upload;  // a mesh sent with the request
  std::string course_mesh_bytes;  // a course's own mesh, when the job names one (embedded ones travel by path)
  std::vector<std::string> warnings;
  // The course's preset the job draws, when it names one: the route asks whether the caller may
  // see it (course/access.h) before any worker draws it.
  const course::Preset* preset = nullptr;
};

// Fields of a JSON body; a 400 for anything but an object.
Expected<RawRequest> from_json_body(const std::string& body);
// Multipart text fields arrive as strings: numbers, booleans and the uniforms object are parsed.
RawRequest from_form(const std::multimap<std::string, std::string>& fields, std::map<std::string, UploadedFile> files);

// The course a request names in its `course` field (its id), or the server's default course.
Expected<const course::Course*> course_of(const RawRequest& raw, const course::CourseSet& courses);

// The job of `course` the request asks for: every fact it leaves out is the course's.
Expected<ParsedJob> parse_job(const RawRequest& raw, worker::JobKind kind, const Limits& limits, const course::Course& course);

// The shaders a request names: its own (uploaded files or inline sources, each within the
// server's size limit) or a preset's name; a 400 for both.
struct RequestShaders {
  std::string preset;
  std::optional<road::ShaderPair> code;
};
Expected<RequestShaders> read_shaders(const RawRequest& raw, const Limits& limits);
// A shader the request sent as an uploaded file (named as uploaded) or as the field's text (named
// `name`, as is an upload without a file name).
Expected<shader::ShaderFile> shader_file(const RawRequest& raw, const char* field, std::string name);

// The mesh file the request uploaded (its `mesh` part), within the limits, with its content
// address and format; none when it sent none.
Expected<std::optional<road::MeshChoice::Upload>> uploaded_mesh(const RawRequest& raw, const Limits& limits);

// Whether a request's field is one the API reads (a render's or a grade's: one job can be sent to
// both routes); any other is ignored with a warning.
bool is_api_field(const std::string& name);

// A mesh id: content-addressed ("m" + 16 hex digits of a 64-bit FNV-1a of the bytes).
std::string mesh_id(const std::string& bytes);

}  // namespace shadelab::http
