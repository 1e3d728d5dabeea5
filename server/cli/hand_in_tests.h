#pragma once
// The tests of a hand-in, the same on every platform that grades it (Gradescope's results.json,
// cli/gradescope_results.h; PrairieLearn's, cli/prairielearn_results.h): for one deliverable
// (docs/grading.md, "On Gradescope"), each worth its share of the checkpoint's points
// (course::TestWeights):
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

// What one deliverable handed in and how it was graded (empty: not graded, nothing to grade).
struct DeliverableGrades {
  const course::Checkpoint* checkpoint = nullptr;
  double points = 0;
  std::optional<std::pair<std::filesystem::path, std::filesystem::path>> code;  // relative to the submission
  course::SavedFrameFiles frames;
  std::optional<Expected<Graded>> code_grade;
  std::optional<Expected<GradedFrames>> frames_grade;
};

// How a test came to its score.
enum class TestOutcome {
  judged,            // the grader compared what was handed in
  nothing_to_grade,  // 0: the hand-in has nothing for it (the words say what was looked for)
  grader_failed,     // 0: the grader's own work failed, not the student's
};

// One test as a student reads it; each platform writes it in its own format.
struct HandInTest {
  std::string name;
  std::optional<course::DeliverableTest> test;  // which of a deliverable's tests; none for an image's
  double score = 0, max_score = 0;
  bool pass = false;
  TestOutcome outcome = TestOutcome::judged;
  std::string grader_error;       // what failed, when the grader did: "a render worker could not start: ..."
  std::string output;             // plain text, one line per finding
  nlohmann::json extra_data;      // the grader's work and the TA's flags; null when none
  std::string heatmap_png;        // a failed test's difference heat map; empty when none
  std::string heatmap_name;       // its file's stem: <checkpoint> or <checkpoint>_frames
};

// The deliverable's tests, in the table's order; `files` is the whole submission (for saying what
// it held when something is missing).
std::vector<HandInTest> deliverable_tests(const course::Course& course, const DeliverableGrades& d,
                                          const std::vector<std::filesystem::path>& files);

// The checked images' tests, in the course's order; each 0 with words on the grader when the
// check could not run.
std::vector<HandInTest> image_tests(const course::Course& course, const Expected<std::vector<grade::ImageCheck>>& checks);

}  // namespace shadelab::cli
