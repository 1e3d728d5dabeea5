#pragma once
// Saved frames as a client hands them in (POST /api/grade with frames): the deliverable they are
// of (a checkpoint, or an alias of one), the files as the page named them, the code beside them
// when there is some, and what the client may change (the mesh, the points). The road alone turns
// them into the grade's submission: the frames put in the deliverable's order by the course's
// names for them, a frame not handed in named, any other file said in a warning. So an adapter
// parses fields and never asks the course, as for code (road/code_request.h).
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/expected.h"
#include "course/course.h"
#include "road/submission.h"

namespace shadelab::road {

struct HandedInFile {
  std::string name;  // as the page saved it: hw2_specular_3.png (a folder before it is ignored)
  std::string bytes;
};

struct FramesRequest {
  std::string reference;  // a checkpoint, or an alias of one
  std::vector<HandedInFile> files;
  std::optional<std::pair<shader::ShaderFile, shader::ShaderFile>> code;  // vertex, fragment
  std::string mesh;                                                     // empty: the course's default
  std::optional<double> max_score;                                      // unset: the checkpoint's points
};

struct BuiltFrames {
  const course::Checkpoint* checkpoint = nullptr;
  FramesSubmission submission;
  FramesSettings settings;  // the mesh and the score; the caller adds its store, heat map and limits
  std::vector<std::string> warnings;
};

// The submission for `request`; a deliverable the course does not have is an Error naming those
// it has. The code's sources are checked where it is graded (grade_saved_frames).
Expected<BuiltFrames> frames_submission(const course::Course& course, FramesRequest request);

}  // namespace shadelab::road
