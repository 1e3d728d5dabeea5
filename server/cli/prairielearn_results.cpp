#include "cli/prairielearn_results.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/base64.h"
#include "core/csv.h"
#include "sheet/narrowed_png.h"

namespace shadelab::cli {

namespace {

using nlohmann::json;

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

// Every text of the results may hold a student's file name: its control characters are shown, not
// obeyed (core/csv.h).
json test_json(const HandInTest& t) {
  const std::string output = printable_lines(t.output);
  return {{"name", printable(t.name)}, {"points", t.score}, {"max_points", t.max_score}, {"message", first_line(output)}, {"output", output}};
}

json image(const std::string& label, const std::string& png, int width) {
  return {{"label", label}, {"url", "data:image/png;base64," + base64_encode(sheet::narrowed_png(png, width))}};
}

// Nothing was judged and the grader failed at least once: the grader could not grade this job.
bool grader_could_not_grade(const HandInResults& r) {
  bool failed = false;
  for (const auto& t : r.tests) {
    if (t.outcome == TestOutcome::judged) return false;
    failed |= t.outcome == TestOutcome::grader_failed;
  }
  return failed;
}

// A grade cut short is no grade: a test the grader did not finish would be a 0 the student did not
// earn. Not gradable (the attempt is not counted), with what was and was not finished.
std::string unfinished(const HandInResults& r) {
  std::string done, not_done;
  for (const auto& t : r.tests) {
    std::string& list = t.outcome == TestOutcome::grader_failed ? not_done : done;
    list += (list.empty() ? "" : "; ") + t.name + (t.outcome == TestOutcome::grader_failed ? "" : t.pass ? " (passed)" : " (failed)");
  }
  return "ShadeLab ran out of the time this question allows before it finished grading, so this attempt is not counted: "
         "this is not a problem with your submission; please submit again, and tell the course staff if it happens again. "
         "Not finished: " + not_done + ". Finished: " + (done.empty() ? "nothing" : done) + ".";
}

// Appends `picture` to the list at `where`, and takes it back out (naming it) when the file would
// pass the limit.
void add_image(json& results, const json::json_pointer& where, json picture, const PrairieLearnLimits& limits, std::vector<std::string>& left_out) {
  const std::string label = picture["label"];
  results[where].push_back(std::move(picture));
  if (results.dump().size() <= limits.max_bytes) return;
  results[where].erase(results[where].size() - 1);
  left_out.push_back(label);
}

}  // namespace

json prairielearn_not_gradable(const std::string& why) { return {{"gradable", false}, {"format_errors", json::array({why})}}; }

json prairielearn_results(const HandInResults& r, const PrairieLearnLimits& limits) {
  if (!r.finished) return prairielearn_not_gradable(unfinished(r));
  if (grader_could_not_grade(r))
    for (const auto& t : r.tests)
      if (t.outcome == TestOutcome::grader_failed)
        return prairielearn_not_gradable("ShadeLab could not grade this submission: " + t.grader_error +
                                         ". This is not a problem with your submission, and the attempt is not counted; please tell the course staff.");
  // A part worth no points (the Blender renders, where the course scores none) loses nothing: a 0
  // there would show the student "0%" in red for renders that match the handout.
  json results = {{"gradable", true},
                  {"score", r.max_score > 0 ? std::clamp(std::round(r.score / r.max_score * 1e6) / 1e6, 0.0, 1.0) : 1.0},
                  {"message", first_line(printable_lines(r.summary))},
                  {"output", printable_lines(r.summary)},
                  {"tests", json::array()},
                  {"images", json::array()}};
  for (const auto& t : r.tests) results["tests"].push_back(test_json(t));
  std::vector<std::string> left_out;
  for (size_t i = 0; i < r.tests.size(); ++i) {
    if (r.tests[i].heatmap_png.empty()) continue;
    const json::json_pointer images("/tests/" + std::to_string(i) + "/images");
    results[images] = json::array();
    add_image(results, images, image("Where your frames differ from the reference (brighter: further off)", r.tests[i].heatmap_png, limits.image_width),
              limits, left_out);
    if (results[images].empty()) results["tests"][i].erase("images");
  }
  for (const auto& grid : r.grids) add_image(results, json::json_pointer("/images"), image(grid.label, grid.png, limits.image_width), limits, left_out);
  for (const auto& label : left_out)
    results["output"] = results["output"].get<std::string>() + "Not shown, to keep the results within PrairieLearn's 1 MB: " + label + "\n";
  return results;
}

}  // namespace shadelab::cli
