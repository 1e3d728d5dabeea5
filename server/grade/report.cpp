#include "grade/report.h"

#include <algorithm>

namespace shadelab::grade {

using nlohmann::json;

namespace {

json optional_number(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

std::optional<double> optional_number(const json& j, const char* key) {
  if (!j.contains(key) || j.at(key).is_null()) return std::nullopt;
  return j.at(key).get<double>();
}

}  // namespace

Report report(const GradeResult& r, const std::string& checkpoint, const std::vector<std::string>& lights,
              size_t frames_per_light) {
  Report out{checkpoint, r.pass, r.score, r.max_score, r.diagnosis, r.messages, {}, {}, {}};
  for (size_t k = 0; k < r.frames.size(); ++k) {
    const size_t set = frames_per_light == 0 ? 0 : k / frames_per_light;
    out.frames.push_back({r.frames[k], set < lights.size() ? lights[set] : "homework"});
  }
  return out;
}

Report failed_submission(const Error& e, const std::string& checkpoint, double max_score) {
  std::string message = e.message;
  for (const auto& d : e.diagnostics)
    if (d.severity == "error") {
      message = (d.line > 0 ? "compile error at " + d.file + " line " + std::to_string(d.line) + ": " : "") + d.message;
      break;
    }
  return {checkpoint, false, 0.0, max_score, std::string(to_string(e.code)), {message}, {}, e.diagnostics, {}};
}

Report part_of(const Report& whole, bool probes, double max_score) {
  Report out = whole;
  out.max_score = max_score;
  out.frames.clear();
  for (const auto& f : whole.frames)
    if ((f.light != "homework") == probes) out.frames.push_back(f);
  out.pass = !out.frames.empty() && std::all_of(out.frames.begin(), out.frames.end(), [](const FrameReport& f) { return f.grade.pass; });
  // A whole that failed for what no frame shows (NaN found in the float frames) fails each part.
  const bool a_frame_fails = std::any_of(whole.frames.begin(), whole.frames.end(), [](const FrameReport& f) { return !f.grade.pass; });
  if (!whole.pass && !a_frame_fails) out.pass = false;
  out.score = out.pass ? max_score : 0;
  if (out.pass) {
    out.diagnosis.clear();
    out.messages = {probes ? "matches the reference under the hidden light" : "matches the reference under the page's light"};
  }
  return out;
}

// The wire: one to_json / from_json pair per struct.

void to_json(json& j, const FrameReport& f) {
  const auto& m = f.grade.metrics;
  j = {{"light", f.light},
       {"pass", f.grade.pass},
       {"identical", m.identical},
       {"rmse", m.rmse},
       {"psnr", m.psnr ? json(*m.psnr) : json(nullptr)},  // null: identical
       {"ssim", m.ssim},
       {"maxAbsError", m.max_abs},
       {"failingFraction", m.failing_fraction},
       {"failingFractionOfObject", f.grade.failing_fraction_of_object},
       {"nanPixels", f.grade.non_finite.nan},
       {"infPixels", f.grade.non_finite.inf},
       {"lagDegrees", optional_number(f.lag_degrees)}};
}

void from_json(const json& j, FrameReport& f) {
  f.light = j.at("light");
  f.grade.pass = j.at("pass");
  auto& m = f.grade.metrics;
  m.identical = j.at("identical");
  m.rmse = j.at("rmse");
  if (!j.at("psnr").is_null()) m.psnr = j.at("psnr").get<double>();
  m.ssim = j.at("ssim");
  m.max_abs = j.at("maxAbsError");
  m.failing_fraction = j.at("failingFraction");
  f.grade.failing_fraction_of_object = j.at("failingFractionOfObject");
  f.grade.non_finite.nan = j.at("nanPixels");
  f.grade.non_finite.inf = j.at("infPixels");
  f.lag_degrees = optional_number(j, "lagDegrees");
}

void to_json(json& j, const Flag& f) { j = {{"id", to_string(f.kind)}, {"message", f.message}}; }

void from_json(const json& j, Flag& f) {
  const auto kind = flag_named(j.at("id").get<std::string>());
  if (!kind) throw json::other_error::create(501, "unknown flag " + j.at("id").dump(), &j);
  f = {*kind, j.at("message")};
}

void to_json(json& j, const Report::GraderWork& w) {
  j = {{"rendered", w.rendered}, {"fromStore", w.from_store}, {"fromMemory", w.from_memory}};
}

void from_json(const json& j, Report::GraderWork& w) { w = {j.at("rendered"), j.at("fromStore"), j.at("fromMemory")}; }

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Explanation::Parameter, name, course, fitted)

void to_json(json& j, const Explanation& e) {
  j = {{"explained", e.explained}, {"variant", e.variant}, {"alsoFits", e.also_fits}, {"parameters", e.parameters},
       {"residual", e.residual}, {"text", e.text}, {"label", e.label}};
}

void from_json(const json& j, Explanation& e) {
  j.at("explained").get_to(e.explained);
  j.at("variant").get_to(e.variant);
  j.at("alsoFits").get_to(e.also_fits);
  j.at("parameters").get_to(e.parameters);
  j.at("residual").get_to(e.residual);
  j.at("text").get_to(e.text);
  j.at("label").get_to(e.label);
}

void to_json(json& j, const Report& r) {
  json frames = r.frames;
  for (size_t k = 0; k < frames.size(); ++k) frames[k]["frame"] = k;  // each frame's index, first
  j = {{"checkpoint", r.checkpoint}, {"pass", r.pass},         {"score", r.score},   {"maxScore", r.max_score},
       {"diagnosis", r.diagnosis},   {"messages", r.messages}, {"frames", frames},   {"diagnostics", r.diagnostics},
       {"warnings", r.warnings},     {"flags", r.flags},       {"attempts", r.attempts}, {"graderWork", r.grader_work}};
  if (r.explanation) j["explanation"] = *r.explanation;
}

void from_json(const json& j, Report& r) {
  r.checkpoint = j.at("checkpoint");
  r.pass = j.at("pass");
  r.score = j.at("score");
  r.max_score = j.at("maxScore");
  r.diagnosis = j.at("diagnosis");
  r.messages = j.at("messages").get<std::vector<std::string>>();
  r.frames = j.at("frames").get<std::vector<FrameReport>>();
  j.at("diagnostics").get_to(r.diagnostics);
  r.warnings = j.at("warnings").get<std::vector<std::string>>();
  r.attempts = j.value("attempts", 1);
  r.flags = j.value("flags", json::array()).get<std::vector<Flag>>();
  if (j.contains("graderWork")) r.grader_work = j.at("graderWork").get<Report::GraderWork>();
  if (j.contains("explanation")) r.explanation = j.at("explanation").get<Explanation>();
}

json to_json(const Report& r) { return r; }

Expected<Report> report_from_json(const json& j) {
  try {
    return j.get<Report>();
  } catch (const json::exception& e) {
    return make_error(ErrorCode::worker_protocol, std::string("malformed grade report: ") + e.what());
  }
}

std::string output_text(const Report& r) {
  std::string output;
  for (const auto& f : r.flags) output += "FLAGGED FOR THE TA: " + f.message + "\n";
  for (const auto& m : r.messages) output += m + "\n";
  return output;
}

json to_gradescope(const Report& r, double seconds) {
  const std::string output = output_text(r);
  json test = {{"name", "checkpoint: " + r.checkpoint},
               {"score", r.score},
               {"max_score", r.max_score},
               {"status", r.pass ? "passed" : "failed"},
               {"output", output},
               {"visibility", "visible"}};
  return {{"score", r.score}, {"execution_time", seconds}, {"output", output}, {"tests", json::array({test})}};
}

}  // namespace shadelab::grade

namespace shadelab {

using nlohmann::json;

void to_json(json& j, const Diagnostic& d) {
  j = {{"stage", d.stage}, {"file", d.file}, {"line", d.line}, {"column", d.column}, {"severity", d.severity},
       {"message", d.message}};
}

void from_json(const json& j, Diagnostic& d) {
  d = {j.value("stage", ""), j.value("file", ""), j.value("line", 0), j.value("column", 0), j.value("severity", "error"),
       j.value("message", "")};
}

}  // namespace shadelab
