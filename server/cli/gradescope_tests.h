#pragma once
// Gradescope's tests for one deliverable (docs/grading.md, "On Gradescope"), each worth its share
// of the checkpoint's points (course::TestWeights):
//
// | test                                   | from                                           |
// |----------------------------------------|------------------------------------------------|
// | <title>: saved frames                  | the frames against the reference, at their lags |
// | <title>: code (<files>)                | the code against the reference, page's light   |
// | <title>: code under a hidden light     | the same under the probe lights, and the rule  |
// | <title>: saved frames made by your code | the frames against the code's render           |
//
// and for each image the course checks (the dolly zoom's cameras), a test worth its points:
//
// | <title> (<file>)                       | the image against the handout's camera         |
//
// A test with nothing to grade (no frames, no code) is 0 with what was looked for; one the grader
// could not grade is 0 with words that put it on the grader.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/grade_runner.h"
#include "course/course.h"
#include "course/submission_files.h"
#include "grade/image_check.h"

namespace shadelab::cli {

struct HeatmapOutput {
  std::string folder;               // written here, <name>.png; empty: not written
  size_t embed_limit = 400 * 1024;  // embedded in the test's output up to this size
};

// What one deliverable handed in and how it was graded (empty: not graded, nothing to grade).
struct DeliverableGrades {
  const course::Checkpoint* checkpoint = nullptr;
  double points = 0;
  std::optional<std::pair<std::filesystem::path, std::filesystem::path>> code;  // relative to the submission
  course::SavedFrameFiles frames;
  std::optional<Expected<Graded>> code_grade;
  std::optional<Expected<GradedFrames>> frames_grade;
};

// The deliverable's tests, in the table's order; `files` is the whole submission (for saying what
// it held when something is missing).
std::vector<nlohmann::json> deliverable_tests(const course::Course& course, const DeliverableGrades& d,
                                              const std::vector<std::filesystem::path>& files, const HeatmapOutput& heatmaps);

// The checked images' tests, in the course's order; each 0 with words on the grader when the
// check could not run.
std::vector<nlohmann::json> image_tests(const course::Course& course, const Expected<std::vector<grade::ImageCheck>>& checks);

}  // namespace shadelab::cli
