#pragma once
// POST /api/grade with the frames a student saved: which deliverable (`reference`, a checkpoint
// or an alias of one), the frames, and the code handed in beside them when `vertex` and
// `fragment` are both given. The frames arrive as multipart parts named `frames` (one per file,
// the file name as the page saved it) or in JSON as `savedFrames`: [{"name", "png": base64}].
// Fields only: the road puts them in frame order by the course's names for them
// (road/frames_request.h).
#include <string>
#include <vector>

#include "core/expected.h"
#include "http/api_request.h"
#include "road/frames_request.h"

namespace shadelab::http {

// Whether the request carries saved frames (and is therefore a grade of them).
bool has_saved_frames(const RawRequest& raw);

struct ParsedFramesGrade {
  road::FramesRequest request;
  std::vector<std::string> warnings;  // fields the grade does not use
};
Expected<ParsedFramesGrade> parse_frames_grade(const RawRequest& raw);

}  // namespace shadelab::http
