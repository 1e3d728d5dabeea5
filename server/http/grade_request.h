#pragma once
// POST /api/grade's fields, read into the road's client-shaped requests. Fields only: what the
// course makes of them is the road's (road/code_request.h, road/frames_request.h).
//
// Code: a render's fields (`width`, `height`, `frames`, `degreesPerFrame`, `msaa`, `uniforms`,
// `mesh`, `fit`), the student's shaders or a `preset`, what they are graded against (`reference`,
// a checkpoint or an alias of one, or `referenceVertex` + `referenceFragment`), the tolerance
// (`threshold`, `maxFailingFraction`, `spatialTolerance`, `maxScore`), and `format`, the result's:
// json or gradescope.
//
// Saved frames: which deliverable (`reference`), the frames, and the code handed in beside them
// when `vertex` and `fragment` are both given. The frames arrive as multipart parts named
// `frames` (one per file, the file name as the page saved it) or in JSON as `savedFrames`:
// [{"name", "png": base64}].
#include <string>
#include <vector>

#include "core/expected.h"
#include "http/api_request.h"
#include "road/client_grade.h"

namespace shadelab::http {

struct ParsedCodeGrade {
  road::CodeRequest request;
  std::string result_format = "json";
  std::vector<std::string> warnings;  // fields the API does not read
};
Expected<ParsedCodeGrade> parse_code_grade(const RawRequest& raw, const Limits& limits);

// Whether the request carries saved frames (and is therefore a grade of them).
bool has_saved_frames(const RawRequest& raw);

struct ParsedFramesGrade {
  road::FramesRequest request;
  std::vector<std::string> warnings;  // fields the grade does not use
};
Expected<ParsedFramesGrade> parse_frames_grade(const RawRequest& raw);

// Either grade, by whether the request carries saved frames, for the road's one call
// (road/client_grade.h). A code grade's field that cannot be read is no error here: it is the
// grade's `unread`, beside the student's sources and the `reference`, `maxScore` and `format` as
// far as they can be read, because the road decides whether the sources are then the grade.
struct ParsedGrade {
  road::ClientGrade grade;
  std::string result_format = "json";  // json, or gradescope for a code grade
};
Expected<ParsedGrade> parse_grade(const RawRequest& raw, const Limits& limits);

}  // namespace shadelab::http
