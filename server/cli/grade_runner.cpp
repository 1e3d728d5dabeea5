#include "cli/grade_runner.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <thread>

#include "grade/grade_session.h"
#include "grade/report.h"
#include "render/render_request.h"

namespace shadelab::cli {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

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

namespace {

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

}  // namespace

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

}  // namespace shadelab::cli
