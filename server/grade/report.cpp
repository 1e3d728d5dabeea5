#include "grade/report.h"

namespace shadelab::grade {

using nlohmann::json;

json to_json(const GradeResult& r, const std::string& checkpoint) {
  json frames = json::array();
  for (size_t k = 0; k < r.frames.size(); ++k) {
    const auto& f = r.frames[k];
    frames.push_back({{"frame", k},
                      {"pass", f.pass},
                      {"identical", f.metrics.identical},
                      {"rmse", f.metrics.rmse},
                      {"psnr", f.metrics.psnr ? json(*f.metrics.psnr) : json(nullptr)},  // null: identical
                      {"ssim", f.metrics.ssim},
                      {"maxAbsError", f.metrics.max_abs},
                      {"failingFraction", f.metrics.failing_fraction},
                      {"failingFractionOfObject", f.failing_fraction_of_object},
                      {"nanPixels", f.non_finite.nan},
                      {"infPixels", f.non_finite.inf}});
  }
  return {{"checkpoint", checkpoint}, {"pass", r.pass},         {"score", r.score}, {"maxScore", r.max_score},
          {"diagnosis", r.diagnosis}, {"messages", r.messages}, {"frames", frames}, {"diagnostics", json::array()}};
}

json failed_submission(const Error& e, const std::string& checkpoint, double max_score) {
  std::string message = e.message;
  for (const auto& d : e.diagnostics)
    if (d.severity == "error") {
      message = (d.line > 0 ? "compile error at " + d.file + " line " + std::to_string(d.line) + ": " : "") + d.message;
      break;
    }
  json diagnostics = json::array();
  for (const auto& d : e.diagnostics)
    diagnostics.push_back({{"stage", d.stage}, {"file", d.file}, {"line", d.line}, {"column", d.column},
                           {"severity", d.severity}, {"message", d.message}});
  return {{"checkpoint", checkpoint}, {"pass", false}, {"score", 0.0}, {"maxScore", max_score},
          {"diagnosis", std::string(to_string(e.code))}, {"messages", json::array({message})},
          {"frames", json::array()}, {"diagnostics", diagnostics}};
}

json to_gradescope(const json& result, double seconds) {
  std::string output;
  for (const auto& m : result.value("messages", json::array())) output += m.get<std::string>() + "\n";
  const bool pass = result.value("pass", false);
  json test = {{"name", "checkpoint: " + result.value("checkpoint", std::string("?"))},
               {"score", result.value("score", 0.0)},
               {"max_score", result.value("maxScore", 1.0)},
               {"status", pass ? "passed" : "failed"},
               {"output", output},
               {"visibility", "visible"}};
  return {{"score", result.value("score", 0.0)}, {"execution_time", seconds}, {"output", output}, {"tests", json::array({test})}};
}

}  // namespace shadelab::grade
