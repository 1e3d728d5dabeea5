#pragma once
// Gradescope's results.json from a graded hand-in (cli/hand_in_grading.h): each test with its
// score, status and words, a failed one's heat map written beside it and embedded in its output
// when small enough, and the summary (with what the TA should look at) on top.
#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/hand_in_grading.h"

namespace shadelab::cli {

struct HeatmapOutput {
  std::string folder;               // written here, <name>.png; empty: not written
  size_t embed_limit = 400 * 1024;  // embedded in the test's output up to this size
};

nlohmann::json gradescope_results(const HandInResults& results, const HeatmapOutput& heatmaps);

}  // namespace shadelab::cli
