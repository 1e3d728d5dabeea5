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
#include "road/code_request.h"
#include "road/frames_request.h"

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

}  // namespace shadelab::http
