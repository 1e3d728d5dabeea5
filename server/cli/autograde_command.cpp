// shadelab autograde SUBMISSION -o results.json: the grading step of a Gradescope autograder
// (gradescope/run_autograder). It finds what a student's submission holds for each deliverable
// (their HW2 folder: the saved frames in images/, the shaders in src/shaders/; or the shader
// modules alone), grades the frames and the code through render workers, all at once, and writes
// Gradescope's results.json: the deliverable's tests (cli/gradescope_tests.h), each worth its share
// of the course's points, a failed one's heat map beside it.
//
// Which files are which deliverable's: course/submission_files.h.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <future>
#include <iostream>
#include <map>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/course_option.h"
#include "cli/file_output.h"
#include "cli/grade_runner.h"
#include "road/hand_in_checks.h"
#include "cli/gradescope_tests.h"
#include "cli/submission_files.h"
#include "course/course_reader.h"
#include "course/submission_files.h"
#include "grade/report.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct AutogradeFlags {
  GradeFlags grade;
  std::optional<double> max_score;  // the course's points per checkpoint when unset
  std::string submission, results, heatmaps;
};

// Each deliverable's files: its shader pair and its saved frames, where the submission has them.
std::vector<DeliverableGrades> deliverables(const course::Course& course, const AutogradeFlags& f, const std::vector<fs::path>& files) {
  const std::vector<course::CheckpointFiles> plan = course::plan_checkpoints(course, files);
  std::vector<DeliverableGrades> out;
  for (const auto& k : course.checkpoints) {
    DeliverableGrades d{&k, f.max_score.value_or(k.points), std::nullopt, course::saved_frame_files(course, k, files), {}, {}};
    for (const auto& p : plan)
      if (p.checkpoint == k.name) d.code = p.pair;
    out.push_back(std::move(d));
  }
  return out;
}

// The grade jobs `out` needs: one for each deliverable's code and one for its frames.
int jobs_for(const std::vector<DeliverableGrades>& out) {
  int jobs = 0;
  for (const auto& d : out) jobs += (d.code ? 1 : 0) + (d.frames.any() ? 1 : 0);
  return jobs;
}

// Each deliverable's grades: every job queued at once (the pool's workers take them in parallel),
// the code's against the reference and the frames' (with the code) side by side.
void grade_all(worker::WorkerPool& pool, const course::Course& course, const AutogradeFlags& f, std::vector<DeliverableGrades>& out) {
  std::vector<std::future<std::optional<Expected<Graded>>>> code;
  std::vector<std::future<std::optional<Expected<GradedFrames>>>> frames;
  for (const auto& d : out) {
    GradeFlags flags = f.grade;
    flags.reference = d.checkpoint->name;
    const fs::path root = f.submission;
    code.push_back(std::async(std::launch::async, [&pool, &course, flags, root, &d]() -> std::optional<Expected<Graded>> {
      if (!d.code) return std::nullopt;
      return grade_one(pool, course, flags, root / d.code->first, root / d.code->second);
    }));
    frames.push_back(std::async(std::launch::async, [&pool, &course, flags, root, &d]() -> std::optional<Expected<GradedFrames>> {
      if (!d.frames.any()) return std::nullopt;
      return grade_saved_frames(pool, course, flags, *d.checkpoint, root, d.frames, d.code);
    }));
  }
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].code_grade = code[i].get();
    out[i].frames_grade = frames[i].get();
  }
}

// The course's checked images (the dolly zoom's cameras), each found as the sheet finds it: at its
// path in the folder, or a path ending in it, the shallowest first.
Expected<std::vector<grade::ImageCheck>> check_images(worker::WorkerPool& pool, const course::Course& course, const fs::path& root,
                                                      const std::vector<fs::path>& files) {
  std::map<std::string, std::string> read;
  return road::check_hand_in_images(pool, course, [&](const std::string& name) -> const std::string* {
    const fs::path* found = course::file_at(files, name);
    return found ? &(read[name] = read_text(root / *found)) : nullptr;
  });
}

int run_autograde(const AutogradeFlags& f) {
  auto loaded = load_course(f.grade.course);
  if (!loaded) return fail(loaded.error());
  const course::Course& course = **loaded;
  const std::vector<fs::path> files = submitted_files(f.submission);
  std::vector<DeliverableGrades> grades = deliverables(course, f, files);
  // As many workers as there are jobs, up to one per core: a submission with one deliverable's
  // code gets one worker with every core's llvmpipe thread, not one of two with half of them.
  worker::WorkerPool pool(pool_config(f.grade, jobs_for(grades)));
  grade_all(pool, course, f, grades);
  json tests = json::array();
  double score = 0, seconds = 0;
  int passed = 0;
  for (const auto& d : grades) {
    for (auto& t : deliverable_tests(course, d, files, {f.heatmaps})) {
      score += t["score"].get<double>();
      passed += t["status"] == "passed";
      tests.push_back(std::move(t));
    }
    if (d.code_grade && *d.code_grade) seconds += (**d.code_grade).seconds;
    if (d.frames_grade && *d.frames_grade) seconds += (**d.frames_grade).seconds;
  }
  for (auto& t : image_tests(course, check_images(pool, course, f.submission, files))) {
    score += t["score"].get<double>();
    passed += t["status"] == "passed";
    tests.push_back(std::move(t));
  }
  std::string summary = std::to_string(passed) + " of " + std::to_string(tests.size()) + " tests passed\n";
  // The flags at the top, where the TA opening the submission reads first.
  for (const auto& d : grades)
    if (d.frames_grade && *d.frames_grade)
      for (const auto& flag : (**d.frames_grade).result.frames.flags)
        summary += "FLAGGED FOR THE TA (" + d.checkpoint->name + " saved frames): " + flag.message + "\n";
  score = std::round(score * 1e6) / 1e6;  // shares of points: 0.4 + 0.2 + ... is not exact in binary
  const json results = {{"score", score}, {"execution_time", seconds}, {"output", summary}, {"tests", tests}};
  if (auto s = write_file(f.results, results.dump(2) + "\n"); !s) return fail(s.error());
  std::cout << summary;
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
  add_grader_options(cmd, f->grade.course, f->grade.cache_dir, f->grade.software);
  cmd->add_option("--max-score", f->max_score, "Points per checkpoint, shared among its tests (default: the course's points for each)");
  cmd->add_option("--timeout-ms", f->grade.timeout_ms, "Compile and render deadline per checkpoint, in CPU time")->capture_default_str();
  return [f] {
    f->grade.heatmaps = f->heatmaps.empty() ? grade::HeatMap::never : grade::HeatMap::when_failing;
    return run_autograde(*f);
  };
}

}  // namespace shadelab::cli
