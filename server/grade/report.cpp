#include "grade/report.h"

#include <algorithm>

#include "core/csv.h"
#include "core/json_fields.h"

namespace shadelab::grade {

using nlohmann::json;
using json_fields::When;

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

std::string mistake_label(const Report& report) {
  if (report.repair_search && report.repair_search->found) {
    const auto& r = *report.repair_search;
    const auto said = [](const Repair& repair) { return repair.label.empty() ? repair.text : repair.label; };
    return said(*r.found) + (r.also ? " + " + said(*r.also) : "");
  }
  return report.explanation ? report.explanation->label : "";
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

// The wire: each struct's fields declared once (core/json_fields.h).

namespace {

constexpr json_fields::Named<FlagKind> kFlagIds{to_string, flag_named};

// The frames in order, each with its index first in the list's reading.
struct NumberedFrames {
  json write(const std::vector<FrameReport>& frames) const {
    json out = frames;
    for (size_t k = 0; k < out.size(); ++k) out[k]["frame"] = k;
    return out;
  }
  void read(const json& j, std::vector<FrameReport>& frames) const { j.get_to(frames); }
};

}  // namespace

SHADELAB_JSON_FIELDS(FrameReport, field("light", &FrameReport::light), at("pass", [](auto& f) -> auto& { return f.grade.pass; }),
                     at("identical", [](auto& f) -> auto& { return f.grade.metrics.identical; }),
                     at("rmse", [](auto& f) -> auto& { return f.grade.metrics.rmse; }),
                     at("psnr", [](auto& f) -> auto& { return f.grade.metrics.psnr; }, When::null_when_empty),  // null: identical
                     at("ssim", [](auto& f) -> auto& { return f.grade.metrics.ssim; }),
                     at("maxAbsError", [](auto& f) -> auto& { return f.grade.metrics.max_abs; }),
                     at("failingFraction", [](auto& f) -> auto& { return f.grade.metrics.failing_fraction; }),
                     at("failingFractionOfObject", [](auto& f) -> auto& { return f.grade.failing_fraction_of_object; }),
                     at("nanPixels", [](auto& f) -> auto& { return f.grade.non_finite.nan; }),
                     at("infPixels", [](auto& f) -> auto& { return f.grade.non_finite.inf; }),
                     field("lagDegrees", &FrameReport::lag_degrees, When::null_when_empty))

SHADELAB_JSON_FIELDS(Flag, field("id", &Flag::kind, kFlagIds), field("message", &Flag::message))

SHADELAB_JSON_FIELDS(Report::GraderWork, field("rendered", &Report::GraderWork::rendered),
                     field("fromStore", &Report::GraderWork::from_store), field("fromMemory", &Report::GraderWork::from_memory))

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Explanation::Parameter, name, course, fitted)

SHADELAB_JSON_FIELDS(Explanation, field("explained", &Explanation::explained), field("variant", &Explanation::variant),
                     field("alsoFits", &Explanation::also_fits), field("parameters", &Explanation::parameters),
                     field("residual", &Explanation::residual), field("text", &Explanation::text), field("label", &Explanation::label))

constexpr json_fields::Named<repair::RepairKind> kRepairKinds{repair::to_string, repair::repair_kind_named};

SHADELAB_JSON_FIELDS(Repair, field("kind", &Repair::kind, kRepairKinds), field("file", &Repair::file, When::omitted_when_empty),
                     field("line", &Repair::line, When::omitted_when_empty),
                     field("text", &Repair::text), field("repairedLine", &Repair::repaired_line, When::omitted_when_empty),
                     field("label", &Repair::label, When::omitted_when_empty))

SHADELAB_JSON_FIELDS(RepairSearch, field("found", &RepairSearch::found, When::omitted_when_empty),
                     field("also", &RepairSearch::also, When::omitted_when_empty),
                     field("candidates", &RepairSearch::candidates), field("confirmations", &RepairSearch::confirmations),
                     field("valuesRead", &RepairSearch::values_read, When::omitted_when_default),
                     field("budgetSpent", &RepairSearch::budget_spent))

SHADELAB_JSON_FIELDS(Report, field("checkpoint", &Report::checkpoint), field("pass", &Report::pass), field("score", &Report::score),
                     field("maxScore", &Report::max_score), field("diagnosis", &Report::diagnosis), field("messages", &Report::messages),
                     field("frames", &Report::frames, NumberedFrames{}), field("diagnostics", &Report::diagnostics),
                     field("warnings", &Report::warnings), field("flags", &Report::flags, When::default_when_missing),
                     field("attempts", &Report::attempts, When::default_when_missing),
                     field("graderWork", &Report::grader_work, When::default_when_missing),
                     field("explanation", &Report::explanation, When::omitted_when_empty),
                     field("repairSearch", &Report::repair_search, When::omitted_when_empty))

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

// A student's file names are in the text: their control characters shown, not obeyed (core/csv.h).
json to_gradescope(const Report& r, double seconds) {
  const std::string output = printable_lines(output_text(r));
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
