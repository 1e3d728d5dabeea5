// shadelab prairielearn ROOT: the grading step of a PrairieLearn external grader (the image's
// entrypoint runs it on /grade; gradescope/'s twin is prairielearn/). It reads the job as
// PrairieLearn lays it out (cli/prairielearn_job.h), grades the student's files by the same road
// as `shadelab autograde` (cli/hand_in_grading.h), and writes ROOT/results/results.json
// (cli/prairielearn_results.h): always, even when the job is malformed or the grader cannot run,
// and before PrairieLearn's time limit, saying what it could not finish.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/course_option.h"
#include "cli/file_output.h"
#include "cli/hand_in_grading.h"
#include "cli/prairielearn_job.h"
#include "cli/prairielearn_results.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

struct PrairieLearnFlags {
  std::string root;
  HandInFlags hand_in{.grid_side = kGridFrameWidth};
  double time_limit_s = 30;  // PrairieLearn's default timeout
};

// PrairieLearn's timeout, as the question's externalGradingOptions.environment passes it.
double time_limit_from_environment() {
  const char* v = std::getenv("SHADELAB_TIME_LIMIT_S");
  char* end = nullptr;
  const double s = v ? std::strtod(v, &end) : 0;
  return v && end != v && s > 0 ? s : 30;
}

// When grading stops: the limit less what writing the results needs and the container's own start
// took, a tenth of the limit and at least 3 s.
Clock::time_point deadline_for(Clock::time_point started, double limit_s) {
  const double margin = std::max(3.0, limit_s / 10);
  return started + std::chrono::milliseconds(static_cast<long>(std::max(0.0, limit_s - margin) * 1000));
}

// The question's own course when its params name one, else the grader's; a question that names a
// checkpoint names one whose code is graded, and `job` then holds its name (an alias resolved).
Expected<std::shared_ptr<const course::Course>> course_for(const PrairieLearnFlags& f, PrairieLearnJob& job) {
  auto loaded = load_course(job.course.empty() ? f.hand_in.grade.course : (fs::path(f.root) / job.course).string());
  if (!loaded) return make_error(ErrorCode::course_invalid, "the question's course cannot be read: " + loaded.error().message);
  if (job.checkpoint.empty()) return loaded;
  auto found = (*loaded)->checkpoint(job.checkpoint);
  if (!found) return make_error(ErrorCode::course_invalid, "the question's params.shadelab.checkpoint: " + found.error().message);
  if (!found->checkpoint->applies(course::DeliverableTest::code))
    return make_error(ErrorCode::course_invalid, "the question's checkpoint '" + job.checkpoint +
                                                     "' is graded by its saved frames alone: a question that takes code needs a checkpoint with code");
  job.checkpoint = found->checkpoint->name;
  return loaded;
}

int write_results(const fs::path& root, const json& results) {
  if (auto s = write_file(root / "results" / "results.json", results.dump(2) + "\n"); !s) return fail(s.error());
  return 0;
}

int run_prairielearn(PrairieLearnFlags f) {
  const Clock::time_point started = Clock::now();
  const fs::path root = f.root;
  std::error_code made;
  fs::create_directories(root / "results", made);  // PrairieLearn does not make it
  auto job = read_prairielearn_job(root);
  if (!job) return write_results(root, prairielearn_not_gradable(job.error().message));
  auto course = course_for(f, *job);
  if (!course) return write_results(root, prairielearn_not_gradable(course.error().message + ". This is not a problem with your submission; please tell the course staff."));
  f.hand_in.checkpoint = job->checkpoint;
  f.hand_in.part = job->part;
  f.hand_in.deadline = deadline_for(started, f.time_limit_s);
  const HandInResults graded = grade_hand_in(**course, f.hand_in, root / "student");
  const int status = write_results(root, prairielearn_results(graded));
  std::cout << graded.summary << std::flush;
  // Work abandoned at the deadline still runs on other threads: leave without waiting for it (its
  // workers die with this process).
  if (!graded.finished) std::_Exit(status);
  return status;
}

}  // namespace

Command add_prairielearn_command(CLI::App& app) {
  auto f = std::make_shared<PrairieLearnFlags>();
  auto* cmd = app.add_subcommand("prairielearn", "Grade a PrairieLearn external-grading job (ROOT/student, ROOT/data/data.json) into ROOT/results/results.json");
  cmd->add_option("root", f->root, "The job's folder, as PrairieLearn lays it out (/grade in its container)")->required()->check(CLI::ExistingDirectory);
  add_grader_options(cmd, f->hand_in.grade.course, f->hand_in.grade.cache_dir, f->hand_in.grade.software);
  f->time_limit_s = time_limit_from_environment();
  cmd->add_option("--time-limit", f->time_limit_s, "PrairieLearn's timeout for the question, in seconds: results are written before it (env SHADELAB_TIME_LIMIT_S)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--timeout-ms", f->hand_in.grade.timeout_ms, "Compile and render deadline per checkpoint, in CPU time")->capture_default_str();
  cmd->add_option("--grid-side", f->hand_in.grid_side, "Pixels a side of each frame in the grids shown to the student (0: none)")->capture_default_str();
  return [f] {
    f->hand_in.grade.heatmaps = grade::HeatMap::when_failing;
    try {
      return run_prairielearn(*f);
    } catch (const std::exception& e) {  // a bug of the grader's: the student still gets a results file that says so
      return write_results(f->root, prairielearn_not_gradable(std::string("ShadeLab failed while grading (") + e.what() +
                                                                 "). This is not a problem with your submission; please tell the course staff."));
    }
  };
}

}  // namespace shadelab::cli
