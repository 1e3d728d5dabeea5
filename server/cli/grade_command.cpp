// shadelab grade: one submission, or a folder of them (one folder per student), graded against a
// checkpoint through render workers, so a submission that hangs or crashes is scored 0 with the
// reason while the batch goes on. With --server, the batch is graded by a ShadeLab server (or a
// cluster behind nginx) instead; --shard splits it over a job array. Both resume (class_batch.h).
#include <filesystem>
#include <iostream>

#include "cli/class_batch.h"
#include "cli/class_frames.h"
#include "cli/commands.h"
#include "cli/course_option.h"
#include "cli/file_output.h"
#include "cli/grade_runner.h"
#include "cli/server_grader.h"
#include "cli/submission_files.h"
#include "core/words.h"
#include "course/course_reader.h"
#include "course/submission_files.h"
#include "grade/report.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

int run_single(const course::Course& c, const GradeFlags& f) {
  worker::WorkerPool pool(pool_config(f, 1));
  auto answered = grade_one(pool, c, f, f.vert, f.frag);
  if (!answered) return fail(answered.error());
  const Graded& graded = *answered;
  const auto& report = graded.result.report;
  const json out = f.format == "gradescope" ? grade::to_gradescope(report, graded.seconds) : grade::to_json(report);
  if (f.output.empty()) std::cout << out.dump(2) << "\n";
  else if (auto s = write_file(f.output, out.dump(2) + "\n"); !s) return fail(s.error());
  if (!f.heatmap.empty() && !graded.result.heatmap_png.empty())
    if (auto s = write_file(f.heatmap, graded.result.heatmap_png); !s) return fail(s.error());
  for (const auto& m : report.messages) std::cerr << m << "\n";
  return 0;
}

// A deliverable's saved frames (found by name under --saved-frames), with --vert/--frag when given:
// {"frames": report, "code": report or null}; the heat map is the frames' against the reference.
int run_saved_frames(const course::Course& c, const GradeFlags& f) {
  auto found = c.checkpoint(f.reference.empty() ? c.default_checkpoint : f.reference);
  if (!found) return fail(found.error());
  const course::Checkpoint& checkpoint = *found->checkpoint;
  const fs::path root = f.saved_frames;
  const course::SavedFrameFiles files = course::saved_frame_files(c, checkpoint, submitted_files(root));
  std::optional<std::pair<fs::path, fs::path>> code;
  if (!f.vert.empty() && !f.frag.empty()) code = std::pair{fs::absolute(f.vert), fs::absolute(f.frag)};
  worker::WorkerPool pool(pool_config(f, 1));
  auto graded = grade_saved_frames(pool, c, f, checkpoint, root, files, code);
  if (!graded) return fail(graded.error());
  const auto& r = graded->result;
  json out = {{"frames", grade::to_json(r.frames)}, {"code", r.code ? grade::to_json(*r.code) : json(nullptr)}};
  for (const auto& extra : files.extra)
    out["frames"]["messages"].push_back(extra.filename().string() + " is not graded: the deliverable has " + std::to_string(c.frames) + " frames");
  if (f.output.empty()) std::cout << out.dump(2) << "\n";
  else if (auto s = write_file(f.output, out.dump(2) + "\n"); !s) return fail(s.error());
  if (!f.heatmap.empty() && !r.heatmap_png.empty())
    if (auto s = write_file(f.heatmap, r.heatmap_png); !s) return fail(s.error());
  for (const auto& flag : r.frames.flags) std::cerr << "frames: FLAGGED FOR THE TA: " << flag.message << "\n";
  for (const auto& m : r.frames.messages) std::cerr << "frames: " << m << "\n";
  if (r.code)
    for (const auto& m : r.code->messages) std::cerr << "code: " << m << "\n";
  return 0;
}

// The POST /api/grade request for one submission, with the same options the in-process batch uses:
// the server's copy of the course (by its id) supplies every fact the flags leave unset.
nlohmann::json server_request(const course::Course& c, const GradeFlags& f, const fs::path& vert, const fs::path& frag) {
  json request = {{"course", c.id}, {"vertex", read_text(vert)}, {"vertexName", vert.filename().string()},
                  {"fragment", read_text(frag)}, {"fragmentName", frag.filename().string()},
                  {"reference", f.reference.empty() ? c.default_checkpoint : f.reference}, {"spatialTolerance", f.spatial},
                  {"maxScore", f.max_score}, {"format", "json"}};
  if (f.threshold) request["threshold"] = *f.threshold;
  if (f.max_failing) request["maxFailingFraction"] = *f.max_failing;
  if (!f.mesh.empty()) request["mesh"] = f.mesh;
  if (f.frames) request["frames"] = *f.frames;
  int width = 0, height = 0;
  if (!f.size.empty() && parse_size(f.size, "--size", width, height)) request["width"] = width, request["height"] = height;
  return request;
}

// A folder without a shader pair is graded 0 with the reason, wherever the batch runs.
std::optional<StudentGrade> without_pair(const course::Course& c, const course::Checkpoint& checkpoint, const GradeFlags& f,
                                         const Student& s, std::optional<std::pair<fs::path, fs::path>>& pair) {
  pair = find_pair(c, s.dir, checkpoint);
  if (pair) return std::nullopt;
  const std::string why = "no shader pair found for " + checkpoint.name + ": expected " + course::wanted_files(c, checkpoint) +
                          " in one folder, or a single *_vert.js and *_frag.js";
  return StudentGrade{road::not_handed_in(why, checkpoint.name, f.max_score), 0, {}};
}

Expected<StudentGrade> grade_student_on_server(const course::Course& c, const course::Checkpoint& checkpoint, const GradeFlags& f,
                                               const ServerOptions& server, const Student& s) {
  std::optional<std::pair<fs::path, fs::path>> pair;
  if (auto zero = without_pair(c, checkpoint, f, s, pair)) return *zero;
  auto graded = grade_on_server(server, server_request(c, f, pair->first, pair->second));
  if (!graded) return graded.take_error();
  return StudentGrade{std::move(graded->report), graded->seconds, {}};
}

Expected<StudentGrade> grade_student(worker::WorkerPool& pool, const course::Course& c, const course::Checkpoint& checkpoint, const GradeFlags& f,
                                     const Student& s, std::vector<repair::PassingProgram> classmates = {}) {
  std::optional<std::pair<fs::path, fs::path>> pair;
  if (auto zero = without_pair(c, checkpoint, f, s, pair)) return *zero;
  if (!classmates.empty()) {
    auto again = grade_beside_class(pool, c, f, pair->first, pair->second, std::move(classmates));
    if (!again) return again.take_error();
    if (!*again) return StudentGrade{{}, 0, {}, true};  // nothing the first search did not try
    return StudentGrade{std::move((*again)->result.report), (*again)->seconds, {}};
  }
  auto graded = grade_one(pool, c, f, pair->first, pair->second);
  if (!graded) return graded.take_error();
  return StudentGrade{std::move(graded->result.report), graded->seconds, {}};
}

// The programs of `passing` students, as each handed them in, for a class batch's second pass.
std::vector<repair::PassingProgram> programs_of(const course::Course& c, const course::Checkpoint& checkpoint, const std::vector<Student>& passing) {
  std::vector<repair::PassingProgram> out;
  for (const auto& s : passing)
    if (const auto pair = find_pair(c, s.dir, checkpoint))
      out.push_back({{pair->first.filename().string(), read_text(pair->first)}, {pair->second.filename().string(), read_text(pair->second)}});
  return out;
}

int run_batch(const course::Course& c, const GradeFlags& f) {
  auto found = c.checkpoint(f.reference.empty() ? c.default_checkpoint : f.reference);
  if (!found) return fail(found.error());
  const course::Checkpoint& checkpoint = *found->checkpoint;
  auto shard = parse_shard(f.shard);
  if (!shard) return fail(shard.error());
  BatchOptions options{f.submissions, f.out, f.concurrency, *shard, checkpoint.name};
  if (!f.server.empty()) {
    const ServerOptions server{f.server, f.api_key, std::chrono::seconds(f.retry_for_s)};
    if (options.concurrency <= 0) options.concurrency = 4;
    const ClassFrames frames(c, checkpoint, [&] { return preset_frames_on_server(server, c.id, checkpoint.reference); });
    return run_class_batch(options, [&](const Student& s) -> Expected<StudentGrade> {
      auto graded = grade_student_on_server(c, checkpoint, f, server, s);
      if (graded) frames.check(s, *graded);
      return graded;
    });
  }
  // In process: as many submissions in flight as the pool has workers, and one more queued.
  size_t count = 0;
  for (const auto& e : fs::directory_iterator(f.submissions)) count += e.is_directory() ? 1 : 0;
  const worker::PoolConfig config = pool_config(f, static_cast<int>(count));
  worker::WorkerPool pool(config);
  if (options.concurrency <= 0) options.concurrency = config.workers + 1;
  const ClassFrames frames(c, checkpoint, [&] { return reference_frames(pool, c, checkpoint); });
  // Each student's results.json is theirs (Gradescope shows it to them): a repair is said as far as
  // the course shows its students (`repairShown`), never the repaired line a TA's single grade shows.
  GradeFlags as_students_see = f;
  as_students_see.show_repaired_line = false;
  const auto grade = [&](const Student& s, std::vector<repair::PassingProgram> classmates) -> Expected<StudentGrade> {
    auto graded = grade_student(pool, c, checkpoint, as_students_see, s, std::move(classmates));
    if (graded && !graded->first_grade_stands) frames.check(s, *graded);
    return graded;  // an error stops the batch, resumable: nobody is graded for the grader's failure
  };
  const auto with_class = [&](const std::vector<Student>& passing) -> GradeStudent {
    return [&grade, classmates = programs_of(c, checkpoint, passing)](const Student& s) { return grade(s, classmates); };
  };
  const bool searched_twice = f.repair_candidates > 0 && f.class_candidates > 0 && !f.warm_store;
  return run_class_batch(options, [&](const Student& s) { return grade(s, {}); }, searched_twice ? GradeWithClass(with_class) : GradeWithClass());
}

}  // namespace

Command add_grade_command(CLI::App& app) {
  auto f = std::make_shared<GradeFlags>();
  auto* cmd = app.add_subcommand("grade", "Grade shaders against a checkpoint (one submission, or a folder of them)");
  add_shader_options(cmd, f->vert, f->frag);
  cmd->add_option("--saved-frames", f->saved_frames,
                  "A folder holding the deliverable's frames as the page saves them (images/hw2_specular_0.png ...): graded "
                  "at the lag each was drawn with, and against --vert/--frag's render when given")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--submissions", f->submissions, "A folder with one folder per student holding their shaders/*.js");
  const course::Course& builtin = course::builtin_course();
  add_grader_options(cmd, f->course, f->cache_dir, f->software);
  cmd->add_option("--reference", f->reference, "A checkpoint of the course (built-in: " + comma_list(builtin.checkpoint_names()) + "; default " +
                                                    builtin.default_checkpoint + ")");
  cmd->add_option("--mesh", f->mesh, "A mesh of the course (default: its default mesh, " + builtin.default_mesh + ")");
  cmd->add_option("--frames", f->frames, "Frames (default: the course's)");
  cmd->add_option("--size", f->size, "Frame size WIDTHxHEIGHT (default: the course's canvas)");
  cmd->add_option("--threshold", f->threshold, "Per-channel difference a pixel may have (default: the course's tolerance, 0.016)");
  cmd->add_option("--max-failing", f->max_failing, "Share of failing pixels a frame may have (default: the course's tolerance, 0.01)");
  cmd->add_flag("--spatial", f->spatial, "Accept a pixel matching the reference within one pixel");
  cmd->add_option("--max-score", f->max_score, "Points for the checkpoint")->capture_default_str();
  cmd->add_option("--format", f->format, "json or gradescope (single submission)")->check(CLI::IsMember({"json", "gradescope"}));
  cmd->add_option("-o,--output", f->output, "Write the result here instead of stdout (single submission)");
  cmd->add_option("--heatmap", f->heatmap, "Write the difference heat map grid PNG here (single submission)");
  cmd->add_option("--out", f->out, "Batch: folder for <student>/results.json and summary.csv")->capture_default_str();
  cmd->add_option("--workers", f->workers, "Render workers (default: one per core)");
  cmd->add_option("--server", f->server, "Batch: grade through this ShadeLab server or cluster (http://HOST:PORT) instead of local workers")
      ->envname("SHADELAB_SERVER");
  cmd->add_option("--api-key", f->api_key, "Batch with --server: the API key to send")->envname("SHADELAB_API_KEY");
  cmd->add_option("--concurrency", f->concurrency, "Batch: submissions in flight at once (default: 4 with --server, else workers + 1)");
  cmd->add_option("--shard", f->shard, "Batch: grade only shard I of N (0 <= I < N), e.g. --shard $SLURM_ARRAY_TASK_ID/8")
      ->capture_default_str();
  cmd->add_option("--retry-for-s", f->retry_for_s, "Batch with --server: how long to keep retrying one submission, then stop")
      ->capture_default_str();
  cmd->add_option("--timeout-ms", f->timeout_ms, "Compile and render deadline per submission, in CPU time (a timeout is retried once)")->capture_default_str();
  cmd->add_option("--repair-candidates", f->repair_candidates,
                  "A failing grade's repair search: edits of the student's program tried, at most (0: no search)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--class-candidates", f->class_candidates,
                  "A class batch: a failing student no search repaired is searched again with this many edits the class's passing "
                  "programs offer, at most (0: no second search)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  f->show_repaired_line = true;  // a TA's machine: the repaired line too
  return [f] {
    auto loaded = load_course(f->course);
    if (!loaded) return fail(loaded.error());
    if (!f->heatmap.empty()) f->heatmaps = grade::HeatMap::always;
    if (!f->submissions.empty()) return run_batch(**loaded, *f);
    if (!f->saved_frames.empty()) return run_saved_frames(**loaded, *f);
    if (f->vert.empty() || f->frag.empty()) {
      std::cerr << "error: give --vert and --frag, or --submissions DIR\n";
      return 2;
    }
    return run_single(**loaded, *f);
  };
}

}  // namespace shadelab::cli
