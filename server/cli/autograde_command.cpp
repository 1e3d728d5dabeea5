// shadelab autograde SUBMISSION -o results.json: the grading step of a Gradescope autograder
// (gradescope/run_autograder). It finds the checkpoints a student's submission holds (their HW2
// folder, or the shader modules alone), grades each through render workers, and writes
// Gradescope's results.json: one test per checkpoint, the heat map of a failed one beside it.
//
// Which files are which checkpoint: course/submission_files.h. Each test is worth the course's
// points for its checkpoint, unless --max-score sets one figure for all.
#include <algorithm>
#include <filesystem>
#include <future>
#include <iostream>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/file_output.h"
#include "cli/course_option.h"
#include "course/course_reader.h"
#include "cli/grade_runner.h"
#include "cli/submission_files.h"
#include "course/submission_files.h"
#include "core/base64.h"
#include "grade/report.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct AutogradeFlags {
  GradeFlags grade;
  std::optional<double> max_score;  // the course's points per checkpoint when unset
  std::string submission, results, heatmaps;
  size_t embed_limit = 400 * 1024;  // heat maps up to this size go into results.json as an image
};

std::string html_escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      default: out += c;
    }
  }
  return out;
}

double points(const AutogradeFlags& f, const course::Checkpoint& c) { return f.max_score.value_or(c.points); }

// A checkpoint the submission has no files for: 0 points, and what was looked for.
json missing_test(const course::Course& course, const course::Checkpoint& c, double max_score, const std::vector<fs::path>& files) {
  return {{"name", c.title}, {"score", 0.0}, {"max_score", max_score}, {"status", "failed"}, {"visibility", "visible"},
          {"output", "no shaders for this checkpoint: expected " + course::wanted_files(course, c) +
                         " in one folder; the submission has " + course::listing(files) + "\n"}};
}

// A graded checkpoint as Gradescope's test, with its heat map (written beside results.json, and
// embedded in the output when small enough) when it failed.
json graded_test(const AutogradeFlags& f, const course::Checkpoint& checkpoint, const std::pair<fs::path, fs::path>& pair,
                 const Graded& graded) {
  json test = grade::to_gradescope(graded.result.report, graded.seconds)["tests"][0];
  test["name"] = checkpoint.title + " (" + pair.first.string() + ", " + pair.second.filename().string() + ")";
  // For the course staff: what the grader rendered for this test, and what it read from its store.
  const auto& w = graded.result.report.grader_work;
  test["extra_data"] = {{"graderWork", {{"rendered", w.rendered}, {"fromStore", w.from_store}, {"fromMemory", w.from_memory}}}};
  const std::string& png = graded.result.heatmap_png;
  if (graded.result.report.pass || png.empty() || f.heatmaps.empty()) return test;
  const fs::path file = fs::path(f.heatmaps) / (checkpoint.name + ".png");
  if (auto written = write_file(file, png); !written) std::cerr << "autograde: " << written.error().message << "\n";
  if (png.size() > f.embed_limit) {
    test["output"] = test["output"].get<std::string>() + "difference heat map: " + file.string() + "\n";
    return test;
  }
  test["output_format"] = "html";
  test["output"] = "<pre>" + html_escape(test["output"].get<std::string>()) +
                   "</pre><p>Where your frames differ from the reference (brighter: further off):</p>"
                   "<img alt=\"difference heat map\" style=\"max-width:100%\" src=\"data:image/png;base64," +
                   base64_encode(png) + "\">";
  return test;
}

// Every checkpoint's grade, all queued at once (the pool's workers take them in parallel); empty
// for a checkpoint with no files.
std::vector<std::optional<Expected<Graded>>> grade_all(worker::WorkerPool& pool, const course::Course& course, const AutogradeFlags& f,
                                                       const std::vector<course::CheckpointFiles>& plan) {
  std::vector<std::future<std::optional<Expected<Graded>>>> pending;
  for (const auto& c : plan)
    pending.push_back(std::async(std::launch::async, [&pool, &course, &f, &c]() -> std::optional<Expected<Graded>> {
      if (!c.pair) return std::nullopt;
      GradeFlags flags = f.grade;
      flags.reference = c.checkpoint;
      flags.max_score = points(f, *course.checkpoint(c.checkpoint)->checkpoint);
      return grade_one(pool, course, flags, fs::path(f.submission) / c.pair->first, fs::path(f.submission) / c.pair->second);
    }));
  std::vector<std::optional<Expected<Graded>>> out;
  for (auto& p : pending) out.push_back(p.get());
  return out;
}

// A checkpoint the grader itself could not grade: 0 on Gradescope (it has no "not graded"), and
// words that put it on the grader, not the student.
json ungraded_test(const course::Checkpoint& c, double max_score, const Error& e) {
  return {{"name", c.title}, {"score", 0.0}, {"max_score", max_score}, {"status", "failed"}, {"visibility", "visible"},
          {"output", "The autograder could not grade this checkpoint: " + e.message + " [" + std::string(info(e.code).name) +
                         "]. This is not a problem with your submission; please tell the course staff.\n"}};
}

int run_autograde(const AutogradeFlags& f) {
  auto loaded = load_course(f.grade.course);
  if (!loaded) return fail(loaded.error());
  const course::Course& course = **loaded;
  const std::vector<fs::path> files = submitted_files(f.submission);
  const std::vector<course::CheckpointFiles> plan = course::plan_checkpoints(course, files);
  worker::WorkerPool pool(pool_config(f.grade, static_cast<int>(std::max<size_t>(plan.size(), 1))));
  const auto grades = grade_all(pool, course, f, plan);
  json tests = json::array();
  double score = 0, seconds = 0;
  int passed = 0;
  for (size_t i = 0; i < plan.size(); ++i) {
    const course::Checkpoint& checkpoint = *course.checkpoint(plan[i].checkpoint)->checkpoint;
    if (!grades[i]) {
      tests.push_back(missing_test(course, checkpoint, points(f, checkpoint), files));
      continue;
    }
    if (!*grades[i]) {
      tests.push_back(ungraded_test(checkpoint, points(f, checkpoint), grades[i]->error()));
      continue;
    }
    const Graded& graded = **grades[i];
    tests.push_back(graded_test(f, checkpoint, *plan[i].pair, graded));
    score += graded.result.report.score;
    seconds += graded.seconds;
    passed += graded.result.report.pass ? 1 : 0;
  }
  const std::string summary = std::to_string(passed) + " of " + std::to_string(plan.size()) + " checkpoints match the reference\n";
  const json results = {{"score", score}, {"execution_time", seconds}, {"output", summary}, {"tests", tests}};
  if (auto s = write_file(f.results, results.dump(2) + "\n"); !s) return fail(s.error());
  std::cout << summary;
  return 0;
}

}  // namespace

Command add_autograde_command(CLI::App& app) {
  auto f = std::make_shared<AutogradeFlags>();
  auto* cmd = app.add_subcommand("autograde", "Grade every checkpoint in a student's submission into Gradescope's results.json");
  cmd->add_option("submission", f->submission, "The submission: the student's HW2 folder, or their shader modules alone")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("-o,--results", f->results, "Where results.json goes")->required();
  cmd->add_option("--heatmaps", f->heatmaps, "Folder for the heat map of each failed checkpoint (<checkpoint>.png)");
  add_course_option(cmd, f->grade.course);
  add_cache_option(cmd, f->grade.cache_dir);
  cmd->add_option("--max-score", f->max_score, "Points per checkpoint (default: the course's points for each)");
  cmd->add_option("--timeout-ms", f->grade.timeout_ms, "Compile and render deadline per checkpoint, in CPU time")->capture_default_str();
  cmd->add_flag("--software", f->grade.software, "Force Mesa's software renderer");
  return [f] { return run_autograde(*f); };
}

}  // namespace shadelab::cli
