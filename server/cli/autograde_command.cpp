// shadelab autograde SUBMISSION -o results.json: the grading step of a Gradescope autograder
// (gradescope/run_autograder). The hand-in (their HW2 folder: the saved frames in images/, the
// shaders in src/shaders/; or the shader modules alone) is graded by cli/hand_in_grading.h and
// written as Gradescope's results.json (cli/gradescope_results.h).
#include <iostream>
#include <optional>

#include "cli/commands.h"
#include "cli/course_option.h"
#include "cli/file_output.h"
#include "cli/gradescope_results.h"
#include "cli/hand_in_grading.h"
#include "course/course_reader.h"

namespace shadelab::cli {

namespace {


struct AutogradeFlags {
  HandInFlags hand_in;
  std::string submission, results, heatmaps;
};

int run_autograde(const AutogradeFlags& f) {
  auto loaded = load_course(f.hand_in.grade.course);
  if (!loaded) return fail(loaded.error());
  const HandInResults graded = grade_hand_in(**loaded, f.hand_in, f.submission);
  if (auto s = write_file(f.results, gradescope_results(graded, {f.heatmaps}).dump(2) + "\n"); !s) return fail(s.error());
  std::cout << graded.summary;
  return 0;
}

}  // namespace

Command add_autograde_command(CLI::App& app) {
  auto f = std::make_shared<AutogradeFlags>();
  auto* cmd = app.add_subcommand("autograde", "Grade every deliverable in a student's submission (saved frames and code) into Gradescope's results.json");
  cmd->add_option("submission", f->submission, "The submission: the student's HW2 folder, or their shader modules alone")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("-o,--results", f->results, "Where results.json goes")->required();
  cmd->add_option("--heatmaps", f->heatmaps, "Folder for the heat map of each failed test (<checkpoint>.png, <checkpoint>_frames.png)");
  add_grader_options(cmd, f->hand_in.grade.course, f->hand_in.grade.cache_dir, f->hand_in.grade.software);
  cmd->add_option("--max-score", f->hand_in.max_score, "Points per checkpoint, shared among its tests (default: the course's points for each)");
  cmd->add_option("--timeout-ms", f->hand_in.grade.timeout_ms, "Compile and render deadline per checkpoint, in CPU time")->capture_default_str();
  return [f] {
    f->hand_in.grade.heatmaps = f->heatmaps.empty() ? grade::HeatMap::never : grade::HeatMap::when_failing;
    return run_autograde(*f);
  };
}

}  // namespace shadelab::cli
