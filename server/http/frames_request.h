#pragma once
// POST /api/grade with the frames a student saved: which deliverable (`reference`, a checkpoint
// or an alias of one), the frames, and the code handed in beside them when `vertex` and
// `fragment` are both given. The frames arrive as multipart parts named `frames` (one per file,
// the file name as the page saved it) or in JSON as `savedFrames`: [{"name", "png": base64}].
// They are put in frame order by the course's names for them (hw2_specular_3.png); a frame not
// handed in is named in the grade, a file that is not one of the deliverable's frames in a warning.
#include <string>
#include <vector>

#include "core/expected.h"
#include "course/course.h"
#include "http/api_request.h"
#include "road/submission.h"

namespace shadelab::http {

// Whether the request carries saved frames (and is therefore a grade of them).
bool has_saved_frames(const RawRequest& raw);

struct ParsedFramesGrade {
  const course::Checkpoint* checkpoint = nullptr;
  road::FramesSubmission submission;
  road::FramesSettings settings;
  std::vector<std::string> warnings;
};
Expected<ParsedFramesGrade> parse_frames_grade(const RawRequest& raw, const course::Course& course);

}  // namespace shadelab::http
