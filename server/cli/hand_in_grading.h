#pragma once
// A student's hand-in graded into tests, the one grader behind every platform's results file
// (`shadelab autograde` for Gradescope, `shadelab prairielearn`): finds what the hand-in holds for
// each deliverable (course/submission_files.h), grades the frames, the code and the checked images
// by the grading road through render workers, all at once, and turns them into the tests of
// cli/hand_in_tests.h.
//
// A platform with a time limit gives a deadline: what has not finished by then is a test the
// grader could not finish (0, on the grader), and the results say so; the work still running is
// abandoned with the process (HandInResults::finished).
#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cli/grade_runner.h"
#include "cli/hand_in_tests.h"
#include "course/course.h"

namespace shadelab::cli {

// Which of the hand-in a grade takes, where a platform takes it in parts (PrairieLearn's upload
// holds 5 MB; a real hand-in is 8.6 MB): the whole; every deliverable's saved frames and code; the
// checked images (the Blender half). A part reports only its own tests: nothing of another part
// is missing from it.
enum class HandInPart { whole, deliverables, images };
std::string_view to_string(HandInPart part);
std::optional<HandInPart> hand_in_part_named(std::string_view name);

struct HandInFlags {
  GradeFlags grade;
  std::optional<double> max_score;  // the course's points per checkpoint when unset
  // Empty: the whole hand-in (every deliverable's tests and the checked images). A checkpoint's
  // name: its code alone, as a question that takes only code grades it (no saved frames).
  std::string checkpoint;
  HandInPart part = HandInPart::whole;  // with no checkpoint
  std::optional<std::chrono::steady_clock::time_point> deadline;
  // > 0: grids for the student to see, each frame this many pixels wide: the frames they saved, or
  // (where they saved none) what their code draws.
  int grid_side = 0;
};

// A grid for the student to see: what they saved, or what their code draws.
struct StudentGrid {
  std::string label;
  std::string png;
};

struct HandInResults {
  std::vector<HandInTest> tests;
  std::vector<StudentGrid> grids;
  std::string summary;          // "2 of 12 tests passed", then what the TA should look at
  double score = 0, max_score = 0;
  double seconds = 0;           // the grader's time inside the grades
  bool finished = true;         // false: the deadline came first; the process must not wait for the rest
};

// The tests of the hand-in under `root` (a folder), graded against `course`.
HandInResults grade_hand_in(const course::Course& course, const HandInFlags& flags, const std::filesystem::path& root);

}  // namespace shadelab::cli
