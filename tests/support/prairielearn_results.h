#pragma once
// What PrairieLearn makes of a results/results.json, re-coded (not copied) from its own code, so a
// change in the shape ShadeLab writes, or in what PrairieLearn accepts, fails a test. Three stages,
// each from PrairieLearn/PrairieLearn:
//   1. the grader host (apps/grader-host/src/index.ts at c09766243): the container must exit 0
//      within its timeout; results.json over 1024 x 1024 bytes or not JSON fails the job;
//   2. makeGradingResult (apps/prairielearn/src/lib/externalGraderCommon.ts at 0e150627a): a
//      `results` object is needed; `format_errors` is kept as a string or an array of them;
//   3. processGradingResult (apps/prairielearn/src/lib/externalGrader.ts at 00eeadb3b): `succeeded`
//      false is a 0; `gradable` defaults to true; a gradable score must be a finite number in
//      [0, 1], else the submission turns not gradable;
// and what pl-external-grader-results shows (its .py at 11f67d02d and .mustache at 37c956829):
// per-test points only when every test has `points` and `max_points`; an image's `url` and `label`.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace shadelab::testkit {

struct PrairieLearnGrading {
  bool job_succeeded = false;  // the grader host's flag: the container ran and its results parsed
  std::string job_message;     // the host's words when it did not
  bool gradable = false;       // what PrairieLearn stores: an attempt counted or not
  double score = 0;            // 0..1, stored only for a gradable submission
  std::string invalid;         // why processGradingResult turned a gradable result not gradable
  std::vector<std::string> format_errors;  // shown in red above the tests
  bool tests_missing_points = false;       // the element then hides every test's points
  std::vector<std::string> image_problems;  // images the element would show broken
};

// JavaScript's truthiness of a parsed JSON value.
inline bool js_truthy(const nlohmann::json& v) {
  if (v.is_null()) return false;
  if (v.is_boolean()) return v.get<bool>();
  if (v.is_number()) return v.get<double>() != 0;
  if (v.is_string()) return !v.get<std::string>().empty();
  return true;
}

inline void check_images(const nlohmann::json& images, const std::string& where, PrairieLearnGrading& g) {
  if (!images.is_array()) return g.image_problems.push_back(where + ": images is not an array");
  for (const auto& image : images) {
    // The template writes `{{url}}` (or the item itself when it has no url) into an <img src>.
    const bool has_url = image.is_object() && image.contains("url") && image["url"].is_string();
    if (!has_url && !image.is_string()) g.image_problems.push_back(where + ": an image without a url");
    else if (has_url && !image["url"].get<std::string>().starts_with("data:image/"))
      g.image_problems.push_back(where + ": an image's url is not a data URI (the student's browser cannot reach the grader)");
  }
}

inline PrairieLearnGrading read_as_prairielearn(const std::string& results_bytes, int exit_status = 0, bool timed_out = false) {
  PrairieLearnGrading g;
  using nlohmann::json;
  // 1. The grader host.
  if (timed_out || exit_status != 0) {
    g.job_message = timed_out ? "did not complete within the time limit" : "the container exited with " + std::to_string(exit_status);
    return g;
  }
  if (results_bytes.size() > 1024u * 1024u) {
    g.job_message = "The grading results were larger than 1MB.";
    return g;
  }
  const json data = json::parse(results_bytes, nullptr, false);
  if (data.is_discarded()) {
    g.job_message = "Could not parse the grading results.";
    return g;
  }
  // 2. makeGradingResult: `results` must be truthy.
  if (!js_truthy(data)) {
    g.job_message = "results did not contain 'results' object.";
    return g;
  }
  g.job_succeeded = true;
  const auto field = [&](const char* name) { return data.is_object() && data.contains(name) ? data[name] : json(); };
  const bool absent_score = !data.is_object() || !data.contains("score");
  if (const json f = field("format_errors"); f.is_string()) g.format_errors = {f.get<std::string>()};
  else if (f.is_array())
    for (const auto& e : f) g.format_errors.push_back(e.is_string() ? e.get<std::string>() : e.dump());
  // 3. processGradingResult: `!!(x ?? true)` for both flags; a score that is not a finite number
  //    (lodash's isFinite: a JS number, so neither "1" nor null) or outside [0, 1] is refused.
  const bool succeeded = field("succeeded").is_null() || js_truthy(field("succeeded"));
  g.gradable = field("gradable").is_null() || js_truthy(field("gradable"));
  if (!g.gradable) return g;
  const json score = succeeded ? field("score") : json(0);
  if (succeeded && absent_score) g.invalid = "score was not provided.";
  else if (!score.is_number()) g.invalid = "score is not a number.";
  else if (score.get<double>() < 0 || score.get<double>() > 1) g.invalid = "score is out of range.";
  else g.score = score.get<double>();
  if (!g.invalid.empty()) g.gradable = false, g.score = 0;
  // The element.
  if (data.is_object() && data.contains("images")) check_images(data["images"], "results", g);
  if (data.is_object() && data.contains("tests") && data["tests"].is_array())
    for (const auto& t : data["tests"]) {
      if (!t.is_object() || !t.contains("points") || !t["points"].is_number() || !t.contains("max_points") || !t["max_points"].is_number())
        g.tests_missing_points = true;
      if (t.is_object() && t.contains("images")) check_images(t["images"], "test " + t.value("name", std::string("?")), g);
    }
  return g;
}

}  // namespace shadelab::testkit
