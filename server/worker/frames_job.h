#pragma once
// A deliverable's saved frames graded through a worker, the one way `shadelab grade
// --saved-frames`, `shadelab autograde` and POST /api/grade send them: against the checkpoint's
// reference and, with the code handed in beside them, against what that code renders. What the
// submission causes (a frame missing, not a PNG, the wrong size; code that cannot be sent) is its
// grade, 0 with the file named; what it does not cause (no worker, a bad mesh name) is an error.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/expected.h"
#include "course/course.h"
#include "worker/client.h"

namespace shadelab::worker {

struct FramesSubmission {
  std::vector<grade::SavedFrame> saved;                                  // in frame order
  std::vector<std::string> missing;                                      // the deliverable's frames not handed in, by file name
  std::string unreadable;  // a file that could not be sent, in words ("hw2_specular_3.png cannot be read"); empty when none
  std::optional<std::pair<shader::ShaderFile, shader::ShaderFile>> code;  // vertex, fragment
};

// Unset facts are the course's (its default mesh); the checkpoint's points are not the score here.
struct FramesGradeSettings {
  std::string mesh;
  double max_score = 1;
  grade::ReferenceStorePlaces reference_store;  // grade/reference_store.h; empty: the worker's memory only
  grade::HeatMap heatmap = grade::HeatMap::always;
};

struct GradedFrames {
  FramesGradeResult result;
  double seconds = 0;
};

Expected<GradedFrames> grade_frame_set(WorkerPool& pool, const course::Course& course, const course::Checkpoint& checkpoint,
                                       FramesSubmission submission, const FramesGradeSettings& settings);

}  // namespace shadelab::worker
