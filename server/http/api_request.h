#pragma once
// Turns what a client sent (a JSON body, multipart/form-data, or a GET query) into a validated
// worker job. Every field is type-checked here; nothing invalid reaches a worker.
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "course/course_set.h"
#include "http/limits.h"
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
  UploadedFile mesh_upload;       // a mesh sent with the request (content empty when none)
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

// A grade request: a render request for the submission, plus `reference` (a checkpoint of the
// course, or an alias of one) or `referenceVertex` + `referenceFragment`, and the tolerance
// (`threshold`, `maxFailingFraction`, `spatialTolerance`, `maxScore`). `format` here is the result's:
// json or gradescope, returned in `result_format`.
struct ParsedGrade {
  ParsedJob parsed;
  std::string result_format = "json";
};
Expected<ParsedGrade> parse_grade_job(RawRequest raw, const Limits& limits, const course::Course& course);

// A mesh id: content-addressed ("m" + 16 hex digits of a 64-bit FNV-1a of the bytes).
std::string mesh_id(const std::string& bytes);

}  // namespace shadelab::http
