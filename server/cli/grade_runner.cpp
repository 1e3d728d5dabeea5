#include "cli/grade_runner.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <thread>

#include "cli/course_option.h"
#include "cli/submission_files.h"
#include "course/submission_files.h"
#include "grade/report.h"
#include "render/render_request.h"
#include "worker/course_job.h"
#include "worker/frames_job.h"

namespace shadelab::cli {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::optional<std::pair<fs::path, fs::path>> find_pair(const course::Course& course, const fs::path& dir, const course::Checkpoint& checkpoint) {
  auto pair = course::checkpoint_pair(course, checkpoint, submitted_files(dir));
  if (!pair) return std::nullopt;
  return std::pair{dir / pair->first, dir / pair->second};
}

namespace {

// The grade job for one submission and its mesh's bytes, built and checked as POST /api/grade builds it.
struct GradeJob {
  worker::Job job;
  std::string payload;
};

Expected<GradeJob> grade_job(const course::Course& c, const GradeFlags& f, shader::ShaderFile vert, shader::ShaderFile frag) {
  grade::GradeOptions options;
  options.compare.threshold = f.threshold;
  options.compare.spatial_tolerance = f.spatial;
  options.max_failing_fraction = f.max_failing;
  options.max_score = f.max_score;
  auto checkpoint = c.checkpoint(f.reference.empty() ? c.default_checkpoint : f.reference);
  if (!checkpoint) return checkpoint.take_error();
  GradeJob out{worker::course_job(c, worker::JobKind::grade), {}};
  worker::Job& job = out.job;
  if (auto s = worker::attach_course_mesh(c, f.mesh.empty() ? c.default_mesh : f.mesh, job, out.payload); !s) return s.take_error();
  job.grade = c.grade_spec(*checkpoint->checkpoint, options);
  job.grade.reference_store.folder = f.cache_dir;
  job.grade.heatmap = f.heatmaps;
  auto& r = job.request;
  r = c.render_request(std::move(vert), std::move(frag));
  if (!f.size.empty())
    if (auto s = parse_size(f.size, "--size", r.width, r.height); !s) return s.take_error();
  r.frames = f.frames.value_or(r.frames);
  const render::RenderLimits limits;
  if (auto valid = render::validate(r, limits); !valid) return valid.take_error();
  if (auto sources = render::check_sources(r, limits); !sources) return sources.take_error();
  return out;
}

}  // namespace

Expected<Graded> grade_one(worker::WorkerPool& pool, const course::Course& c, const GradeFlags& f, const fs::path& vert,
                           const fs::path& frag) {
  return grade_pair(pool, c, f, {vert.filename().string(), read_text(vert)}, {frag.filename().string(), read_text(frag)});
}

Expected<Graded> grade_pair(worker::WorkerPool& pool, const course::Course& c, const GradeFlags& f, shader::ShaderFile vert,
                            shader::ShaderFile frag) {
  const std::string checkpoint = f.reference.empty() ? c.default_checkpoint : f.reference;
  const auto ungradable = [&](Error e) -> Expected<Graded> {
    if (!info(e.code).submission_caused) return e;
    return Graded{{grade::failed_submission(e, checkpoint, f.max_score), {}}, 0};
  };
  auto job = grade_job(c, f, std::move(vert), std::move(frag));
  if (!job) return ungradable(job.take_error());
  auto answered = worker::grade(pool, job->job, std::move(job->payload));
  if (!answered) return ungradable(answered.take_error());
  return Graded{std::move(answered->result), (answered->queue_ms + answered->worker_ms) / 1000};
}

namespace {

worker::FramesGradeSettings frames_settings(const GradeFlags& f) { return {f.mesh, f.max_score, {.folder = f.cache_dir}, f.heatmaps}; }

}  // namespace

Expected<GradedFrames> grade_frame_set(worker::WorkerPool& pool, const course::Course& c, const GradeFlags& f,
                                       const course::Checkpoint& checkpoint, std::vector<grade::SavedFrame> saved,
                                       const std::optional<std::pair<shader::ShaderFile, shader::ShaderFile>>& code) {
  return worker::grade_frame_set(pool, c, checkpoint, {std::move(saved), {}, {}, code}, frames_settings(f));
}

Expected<GradedFrames> grade_saved_frames(worker::WorkerPool& pool, const course::Course& c, const GradeFlags& f,
                                          const course::Checkpoint& checkpoint, const fs::path& root, const course::SavedFrameFiles& files,
                                          const std::optional<std::pair<fs::path, fs::path>>& code) {
  worker::FramesSubmission submission{{}, files.missing(c, checkpoint), {}, std::nullopt};
  if (code)
    submission.code = std::pair{shader::ShaderFile{code->first.filename().string(), read_text(root / code->first)},
                                shader::ShaderFile{code->second.filename().string(), read_text(root / code->second)}};
  for (const auto& frame : files.frames) {
    if (!frame || !submission.missing.empty()) break;
    std::error_code ec;
    const auto bytes = fs::file_size(root / *frame, ec);
    if (ec || bytes > kMaxFrameBytes) {
      submission.unreadable = frame->filename().string() + (ec ? " cannot be read" : " is larger than a saved frame can be (32 MB)");
      break;
    }
    submission.saved.push_back({frame->filename().string(), read_text(root / *frame)});
  }
  return worker::grade_frame_set(pool, c, checkpoint, std::move(submission), frames_settings(f));
}

worker::PoolConfig pool_config(const GradeFlags& f, int jobs) {
  worker::PoolConfig c;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  c.workers = f.workers > 0 ? f.workers : std::min(cores, std::max(1, jobs));
  c.llvmpipe_threads = std::max(1, cores / c.workers);
  c.compile_deadline = c.render_deadline = std::chrono::milliseconds(f.timeout_ms);
  c.max_queue = static_cast<size_t>(std::max(jobs, 1));
  c.force_software = f.software;
  c.warm_up = worker::WarmUp::none;  // the jobs are queued at once: a warm-up would only delay the first
  return c;
}

}  // namespace shadelab::cli
