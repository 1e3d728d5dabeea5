// shadelab grade: one submission, or a folder of them (one folder per student), graded against a
// checkpoint through render workers, so a submission that hangs or crashes is scored 0 with the
// reason while the batch goes on. With --server, the batch is graded by a ShadeLab server (or a
// cluster behind nginx) instead; --shard splits it over a job array. Both resume (class_batch.h).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <thread>

#include "cli/class_batch.h"
#include "cli/commands.h"
#include "cli/file_output.h"
#include "cli/server_grader.h"
#include "cli/environment.h"
#include "grade/report.h"
#include "grade/grade_session.h"
#include "render/render_request.h"
#include "worker/client.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct GradeFlags {
  std::string vert, frag, submissions, reference = "specular", mesh = "bunny", out = "grades", output, heatmap;
  std::string format = "json", size = "640x480";
  int frames = 9, workers = 0, concurrency = 0;
  std::string server, api_key, shard = "0/1";
  long retry_for_s = 300;
  double threshold = 0.016, max_failing = 0.01, max_score = 1.0;
  bool spatial = false;
  long timeout_ms = 10000;
  bool software = software_from_environment();
};

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// The submission's shader pair: the homework's file names for the checkpoint first, else the only
// *_vert.js / *_frag.js pair in the folder.
std::optional<std::pair<fs::path, fs::path>> find_pair(const fs::path& dir, const std::string& checkpoint) {
  std::vector<fs::path> verts, frags;
  for (const auto& e : fs::recursive_directory_iterator(dir, fs::directory_options::skip_permission_denied)) {
    const std::string name = e.path().filename().string();
    if (name.ends_with("_vert.js")) verts.push_back(e.path());
    if (name.ends_with("_frag.js")) frags.push_back(e.path());
  }
  const std::string stem = checkpoint == "smooth" || checkpoint == "gouraud" ? "starter" : "phong";
  for (const auto& v : verts)
    for (const auto& f : frags)
      if (v.filename() == stem + "_vert.js" && f.filename() == stem + "_frag.js") return std::pair{v, f};
  if (verts.size() == 1 && frags.size() == 1) return std::pair{verts[0], frags[0]};
  return std::nullopt;
}

// The grade job for one submission, built and checked as POST /api/grade builds it.
Expected<worker::Job> grade_job(const GradeFlags& f, const fs::path& vert, const fs::path& frag) {
  grade::GradeOptions options;
  options.compare.threshold = f.threshold;
  options.compare.spatial_tolerance = f.spatial;
  options.max_failing_fraction = f.max_failing;
  options.max_score = f.max_score;
  auto spec = grade::checkpoint_spec(f.reference, options);
  if (!spec) return spec.take_error();
  worker::Job job;
  job.kind = worker::JobKind::grade;
  job.mesh = f.mesh;
  job.grade = std::move(*spec);
  auto& r = job.request;
  if (std::sscanf(f.size.c_str(), "%dx%d", &r.width, &r.height) != 2)
    return make_error(ErrorCode::invalid_argument, "--size takes WIDTHxHEIGHT, e.g. 640x480; got '" + f.size + "'");
  r.frames = f.frames;
  r.vertex = {vert.filename().string(), read_text(vert)};
  r.fragment = {frag.filename().string(), read_text(frag)};
  const render::RenderLimits limits;
  if (auto valid = render::validate(r, limits); !valid) return valid.take_error();
  if (auto sources = render::check_sources(r, limits); !sources) return sources.take_error();
  return job;
}

// One submission to a grade, whatever goes wrong with it.
struct Graded {
  worker::GradeResult result;
  double seconds = 0;
};

Graded grade_one(worker::WorkerPool& pool, const GradeFlags& f, const fs::path& vert, const fs::path& frag) {
  const auto ungradable = [&](const Error& e) { return Graded{{grade::failed_submission(e, f.reference, f.max_score), {}}, 0}; };
  auto job = grade_job(f, vert, frag);
  if (!job) return ungradable(job.error());
  auto answered = worker::grade(pool, *job, "");
  if (!answered) return ungradable(answered.error());
  return {std::move(answered->result), (answered->queue_ms + answered->worker_ms) / 1000};
}



worker::PoolConfig pool_config(const GradeFlags& f, int jobs) {
  worker::PoolConfig c;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  c.workers = f.workers > 0 ? f.workers : std::min(cores, std::max(1, jobs));
  c.llvmpipe_threads = std::max(1, cores / c.workers);
  c.compile_deadline = c.render_deadline = std::chrono::milliseconds(f.timeout_ms);
  c.max_queue = static_cast<size_t>(std::max(jobs, 1));
  c.force_software = f.software;
  return c;
}

int run_single(const GradeFlags& f) {
  worker::WorkerPool pool(pool_config(f, 1));
  const Graded graded = grade_one(pool, f, f.vert, f.frag);
  const auto& report = graded.result.report;
  const json out = f.format == "gradescope" ? grade::to_gradescope(report, graded.seconds) : grade::to_json(report);
  if (f.output.empty()) std::cout << out.dump(2) << "\n";
  else if (auto s = write_file(f.output, out.dump(2) + "\n"); !s) return fail(s.error());
  if (!f.heatmap.empty() && !graded.result.heatmap_png.empty())
    if (auto s = write_file(f.heatmap, graded.result.heatmap_png); !s) return fail(s.error());
  for (const auto& m : report.messages) std::cerr << m << "\n";
  return 0;
}

// The POST /api/grade request for one submission, with the same options the in-process batch uses.
nlohmann::json server_request(const GradeFlags& f, const fs::path& vert, const fs::path& frag) {
  int width = 0, height = 0;
  std::sscanf(f.size.c_str(), "%dx%d", &width, &height);
  return {{"vertex", read_text(vert)}, {"vertexName", vert.filename().string()}, {"fragment", read_text(frag)},
          {"fragmentName", frag.filename().string()}, {"reference", f.reference}, {"mesh", f.mesh}, {"frames", f.frames},
          {"width", width}, {"height", height}, {"threshold", f.threshold}, {"maxFailingFraction", f.max_failing},
          {"spatialTolerance", f.spatial}, {"maxScore", f.max_score}, {"format", "json"}};
}

// A folder without a shader pair is graded 0 with the reason, wherever the batch runs.
std::optional<StudentGrade> without_pair(const GradeFlags& f, const Student& s, std::optional<std::pair<fs::path, fs::path>>& pair) {
  pair = find_pair(s.dir, f.reference);
  if (pair) return std::nullopt;
  return StudentGrade{grade::failed_submission(make_error(ErrorCode::invalid_argument, "no shader pair found (expected *_vert.js and *_frag.js)"),
                                               f.reference, f.max_score), 0};
}

int run_batch(const GradeFlags& f) {
  auto shard = parse_shard(f.shard);
  if (!shard) return fail(shard.error());
  BatchOptions options{f.submissions, f.out, f.concurrency, *shard};
  if (!f.server.empty()) {
    const ServerOptions server{f.server, f.api_key, std::chrono::seconds(f.retry_for_s)};
    if (options.concurrency <= 0) options.concurrency = 4;
    return run_class_batch(options, [&](const Student& s) -> Expected<StudentGrade> {
      std::optional<std::pair<fs::path, fs::path>> pair;
      if (auto zero = without_pair(f, s, pair)) return *zero;
      auto graded = grade_on_server(server, server_request(f, pair->first, pair->second));
      if (!graded) return graded.take_error();
      return StudentGrade{std::move(graded->report), graded->seconds};
    });
  }
  // In process: as many submissions in flight as the pool has workers, and one more queued.
  size_t count = 0;
  for (const auto& e : fs::directory_iterator(f.submissions)) count += e.is_directory() ? 1 : 0;
  const worker::PoolConfig config = pool_config(f, static_cast<int>(count));
  worker::WorkerPool pool(config);
  if (options.concurrency <= 0) options.concurrency = config.workers + 1;
  return run_class_batch(options, [&](const Student& s) -> Expected<StudentGrade> {
    std::optional<std::pair<fs::path, fs::path>> pair;
    if (auto zero = without_pair(f, s, pair)) return *zero;
    Graded graded = grade_one(pool, f, pair->first, pair->second);
    return StudentGrade{std::move(graded.result.report), graded.seconds};
  });
}

}  // namespace

Command add_grade_command(CLI::App& app) {
  auto f = std::make_shared<GradeFlags>();
  auto* cmd = app.add_subcommand("grade", "Grade shaders against a checkpoint (one submission, or a folder of them)");
  cmd->add_option("--vert", f->vert, "Submission's vertex shader");
  cmd->add_option("--frag", f->frag, "Submission's fragment shader");
  cmd->add_option("--submissions", f->submissions, "A folder with one folder per student holding their shaders/*.js");
  cmd->add_option("--reference", f->reference, "Checkpoint: smooth, gouraud, diffuse, specular")->capture_default_str();
  cmd->add_option("--mesh", f->mesh, "Built-in mesh")->capture_default_str();
  cmd->add_option("--frames", f->frames, "Frames")->capture_default_str();
  cmd->add_option("--size", f->size, "Frame size")->capture_default_str();
  cmd->add_option("--threshold", f->threshold, "Per-channel difference a pixel may have")->capture_default_str();
  cmd->add_option("--max-failing", f->max_failing, "Share of failing pixels a frame may have")->capture_default_str();
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
  cmd->add_flag("--software", f->software, "Force Mesa's software renderer");
  return [f] {
    if (!f->submissions.empty()) return run_batch(*f);
    if (f->vert.empty() || f->frag.empty()) {
      std::cerr << "error: give --vert and --frag, or --submissions DIR\n";
      return 2;
    }
    return run_single(*f);
  };
}

}  // namespace shadelab::cli
