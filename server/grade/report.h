#pragma once
// A grade as the student, the TA and Gradescope see it. One shape, whether the submission was
// graded frame by frame or could not be graded at all (it does not compile, hangs, crashes the
// driver: score 0 and the reason). It crosses the worker boundary and is the body of
// POST /api/grade and of `shadelab grade`'s results, so to_json and report_from_json are its wire.
//
// | JSON field   | meaning                                                                    |
// |--------------|----------------------------------------------------------------------------|
// | checkpoint   | the course's checkpoint (normals, diffuse, specular), or custom            |
// | pass, score, maxScore | the verdict; a code grade scores maxScore x the share of frames     |
// |              | that pass, saved frames all or nothing                                     |
// | diagnosis    | the recognised mistake's id, "swapped_channels", "nan", an error code, ""  |
// | messages[]   | what the student reads, most important first                               |
// | frames[]     | per frame and light: metrics, failing share of the object, NaN/Inf counts; |
// |              | lagDegrees for a frame the student saved                                   |
// | diagnostics[]| compiler messages at the student's lines (ungradable submissions)          |
// | warnings[]   | request fields ignored, uniforms the program does not use, ...             |
// | flags[]      | {id, message} for the TA: saved frames ShadeLab made, frames with no lag   |
// |              | (grade/provenance.h)                                                       |
// | graderWork   | the grader's own sets of frames: rendered, fromStore (disk/Redis), fromMemory    |
// | repairSearch | a failing code grade's repair: the line to change, what is wrong, counts    |
// |              | (road/repair_search.h)                                                      |
// | explanation  | a failing grade's reading by the checkpoint's formula (grade/formula_explanation.h): |
// |              | the change that reproduces the frames, the values it fits, the residual     |
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "core/json_fields.h"
#include "repair/repair_edit.h"
#include "grade/grader.h"
#include "grade/provenance.h"

namespace shadelab::grade {

struct FrameReport {
  FrameGrade grade;
  std::string light = "homework";  // "homework", or the probe light it was rendered under
  // A saved frame's: how far behind its nominal angle it was drawn (grade/lag_fit.h).
  std::optional<double> lag_degrees;
};

// Why a failing submission's frames differ, read by the checkpoint's formula: the one change to it
// (or two) that reproduces them within the rule a correct submission meets, or none.
struct Explanation {
  bool explained = false;
  // The formula's structural change ("light_as_direction"; "formula" when only values changed);
  // when nothing reproduces the frames, the closest.
  std::string variant;
  std::vector<std::string> also_fits;  // other explanations that reproduce the frames as well
  struct Parameter {
    std::string name;                   // ambient, diffuse, specular, exponent
    std::vector<double> course, fitted;  // what the course has and what the frames show
  };
  std::vector<Parameter> parameters;  // the values the frames show changed
  double residual = 0;  // the worst frame's share of interior object pixels the explanation draws off
  std::string text;     // in the homework's words, with the numbers
  std::string label;    // a few words, to count a class by: "light used as a direction", "not explained"
};

// A failing code grade's repair (road/repair_search.h): the smallest edit of the student's own
// program that makes it draw what the reference draws, confirmed on every frame the grade draws.
struct Repair {
  repair::RepairKind kind = repair::RepairKind::normalised;
  // Where: the student's file (phong_frag.js) and its line (1-based); none where the course shows
  // its students only what is wrong (RepairShown::what).
  std::optional<std::string> file;
  std::optional<int> line;
  std::string text;  // what is wrong there, in the homework's words
  // The line as the repair writes it: for whoever may see the references (a TA, an open server),
  // and for students only where their course shows it (RepairShown::repaired_line).
  std::optional<std::string> repaired_line;
  // The mistake in a few words, alike for every student who made it: the formula's name for the
  // vector where the subject is one, never the student's own ("L not normalised"). A class is
  // counted by it (cli/class_batch.cpp).
  std::string label;
};

// What the repair search of a failing code grade tried, counted (not timed): the same on any machine.
struct RepairSearch {
  std::optional<Repair> found;
  std::optional<Repair> also;  // a repair of two edits: the second
  int candidates = 0;     // edits screened, each its own worker job on a small canvas
  int confirmations = 0;  // screened passes rendered again at the grade's own frames
  // Candidates whose program's values were read on the small canvas, to say where a second mistake
  // is (repair/search_order.h); the student's own, read by the verdict, not counted.
  int values_read = 0;
  bool budget_spent = false;  // every candidate the budget allows was tried and none was confirmed
};

struct Report {
  std::string checkpoint;
  bool pass = false;
  double score = 0, max_score = 1;
  std::string diagnosis;
  std::vector<std::string> messages;
  std::vector<FrameReport> frames;
  std::vector<Diagnostic> diagnostics;
  std::vector<std::string> warnings;
  std::vector<Flag> flags;  // for the TA to look at (grade/provenance.h)
  int attempts = 1;  // 2 when the first ran past its deadline and the grade is the retry's
  // The grader's own work for this grade, in sets of frames (one light's render of the reference
  // or of one known mistake): rendered, read from the store on disk, or found in the worker's memory.
  struct GraderWork {
    int rendered = 0, from_store = 0, from_memory = 0;
  } grader_work;
  std::optional<Explanation> explanation;  // a failing grade's, where the checkpoint has a formula
  std::optional<RepairSearch> repair_search;  // a failing code grade's that nothing else explained
};

// A graded result; `lights` names the light of each run of frames_per_light frames, in order.
Report report(const GradeResult& result, const std::string& checkpoint, const std::vector<std::string>& lights,
              size_t frames_per_light);
// A submission that could not be graded: score 0, the reason (its first compile error at its line).
Report failed_submission(const Error& error, const std::string& checkpoint, double max_score);

// A failing grade's mistake in a few words, to count a class by: its confirmed repair's words
// ("`L` is not normalised: a direction must be a unit vector", a repair of two edits both joined
// by " + "), else the formula's label; "" for neither. Never the line or the repaired line:
// students share a mistake, not a line number.
std::string mistake_label(const Report& report);

// The part of a report under the page's light (`probes` false) or under the probe lights (true),
// worth `max_score`: a submission right under the page's light and wrong under a probe sees which.
// A report with no frames (the code did not compile) is the same failure for either part.
Report part_of(const Report& whole, bool probes, double max_score);

// The wire, one declaration per struct (nlohmann finds these pairs by their argument's type);
// `from_json` throws nlohmann::json::exception on a malformed report.
SHADELAB_JSON_DECLARE(FrameReport);  // its index ("frame") is the report's to write
SHADELAB_JSON_DECLARE(Flag);
SHADELAB_JSON_DECLARE(Report::GraderWork);
SHADELAB_JSON_DECLARE(Explanation::Parameter);
SHADELAB_JSON_DECLARE(Explanation);
SHADELAB_JSON_DECLARE(Repair);
SHADELAB_JSON_DECLARE(RepairSearch);
SHADELAB_JSON_DECLARE(Report);

nlohmann::json to_json(const Report& report);
// A malformed report is worker_protocol.
Expected<Report> report_from_json(const nlohmann::json& j);

// What a test's output says: the flags first ("FLAGGED FOR THE TA: ..."), then the messages, a
// line each.
std::string output_text(const Report& report);

// Gradescope's results.json: score, execution_time, output, tests[] (name, score, max_score,
// status, output, visibility).
nlohmann::json to_gradescope(const Report& report, double execution_seconds);

}  // namespace shadelab::grade

namespace shadelab {
// A diagnostic as a report and the worker carry it. Reading is lenient (a missing field is its
// default): the worker that sends one runs student code.
SHADELAB_JSON_DECLARE(Diagnostic);
}  // namespace shadelab
