#pragma once
// PrairieLearn's results.json (its external-grading documentation, "Grading results") from a
// graded hand-in (cli/hand_in_grading.h):
//
//   score        the points the tests gave over the points they were worth, in [0, 1]
//   output       the summary a Gradescope student reads at the top
//   tests[]      name, points, max_points, message (the test's first line), output (its words, the
//                same as on Gradescope), images (a failed test's difference heat map)
//   images[]     the student's grids: the frames they saved, what their code draws
//
// PrairieLearn keeps a results file to 1 MB: the images go in, most useful first (a failed test's
// heat map, then the grids), each narrowed to a size to look at, while the whole file stays under
// the limit; one left out is named in the output. A job the grader could not grade at all (no
// test judged: no GL here, every render failed) is `gradable: false` with why, so the student is
// not charged an attempt for the grader's failure; so is a malformed job.
#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/hand_in_grading.h"

namespace shadelab::cli {

// Each frame's width in the grids PrairieLearn's results show: small enough that every grid of a
// hand-in and the failed tests' heat maps fit in PrairieLearn's 1 MB (the built-in course's whole
// hand-in with one test failing measured ~640 KB).
inline constexpr int kGridFrameWidth = 160;

struct PrairieLearnLimits {
  size_t max_bytes = 1000 * 1000 - 16 * 1024;  // PrairieLearn's 1 MB, less room for its own framing
  int image_width = 768;                        // images wider than this are narrowed
};

nlohmann::json prairielearn_results(const HandInResults& results, const PrairieLearnLimits& limits = {});

// The job cannot be graded: `why` for the student and staff, and no score.
nlohmann::json prairielearn_not_gradable(const std::string& why);

}  // namespace shadelab::cli
