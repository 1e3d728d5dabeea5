#include "cli/grade_runner.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <thread>

#include "cli/course_option.h"
#include "cli/submission_files.h"
#include "core/cpu_budget.h"
#include "course/submission_files.h"
#include "grade/report.h"
#include "road/code_request.h"
#include "render/render_request.h"

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

// The course's submission of the pair, as the flags draw it: the checkpoint's tolerance with what
// the flags set.
Expected<road::CodeSubmission> submission_of(const course::Course& c, const GradeFlags& f, shader::ShaderFile vert, shader::ShaderFile frag) {
  road::CodeRequest request;
  request.code = road::ShaderPair{std::move(vert), std::move(frag)};
  request.reference = f.reference.empty() ? c.default_checkpoint : f.reference;
  request.mesh.name = f.mesh;
  request.render.frames = f.frames;
  if (!f.size.empty()) {
    int width = 0, height = 0;
    if (auto s = parse_size(f.size, "--size", width, height); !s) return s.take_error();
    request.render.width = width;
    request.render.height = height;
  }
  request.tolerance = {f.threshold, f.max_failing, f.max_score, f.spatial};
  auto built = road::code_submission(c, std::move(request), course::Viewer{}, {});
  if (!built) return built.take_error();
  road::CodeSubmission& submission = built->submission;
  submission.spec.reference_store.folder = f.cache_dir;
  submission.spec.heatmap = f.heatmaps;
  submission.repair.candidates = f.warm_store ? 0 : f.repair_candidates;
  submission.repair.class_candidates = f.class_candidates;
  submission.spec.warm = f.warm_store;
  if (f.show_repaired_line) {  // a TA's own grade: the repaired line and every pixel of the difference
    submission.repair_shown = repair::RepairShown::repaired_line;
    submission.spec.picture = grade::DifferencePicture::full;
  }
  return std::move(submission);
}

}  // namespace

Expected<Graded> grade_one(worker::WorkerPool& pool, const course::Course& c, const GradeFlags& f, const fs::path& vert,
                           const fs::path& frag) {
  return grade_pair(pool, c, f, {vert.filename().string(), read_text(vert)}, {frag.filename().string(), read_text(frag)});
}

Expected<Graded> grade_pair(worker::WorkerPool& pool, const course::Course& c, const GradeFlags& f, shader::ShaderFile vert,
                            shader::ShaderFile frag) {
  auto submission = submission_of(c, f, std::move(vert), std::move(frag));
  if (!submission) return submission.take_error();
  return road::grade_code(pool, std::move(*submission));
}

Expected<std::optional<Graded>> grade_beside_class(worker::WorkerPool& pool, const course::Course& c, const GradeFlags& f,
                                                   const fs::path& vert, const fs::path& frag, std::vector<repair::PassingProgram> classmates) {
  auto submission = submission_of(c, f, {vert.filename().string(), read_text(vert)}, {frag.filename().string(), read_text(frag)});
  if (!submission) return submission.take_error();
  submission->classmates = std::move(classmates);
  if (!road::second_search_has_candidates(*submission)) return std::optional<Graded>();
  auto graded = road::grade_code(pool, std::move(*submission));
  if (!graded) return graded.take_error();
  return std::optional<Graded>(std::move(*graded));
}

namespace {

road::FramesSettings frames_settings(const GradeFlags& f) {
  road::FramesSettings s{f.mesh, f.max_score, {.folder = f.cache_dir}, f.heatmaps};
  if (f.show_repaired_line) s.picture = grade::DifferencePicture::full;  // a TA's own grade
  return s;
}

}  // namespace

Expected<GradedFrames> grade_frame_set(worker::WorkerPool& pool, const course::Course& c, const GradeFlags& f,
                                       const course::Checkpoint& checkpoint, std::vector<grade::SavedFrame> saved,
                                       const std::optional<std::pair<shader::ShaderFile, shader::ShaderFile>>& code) {
  return road::grade_saved_frames(pool, c, checkpoint, {std::move(saved), {}, {}, code}, frames_settings(f));
}

Expected<GradedFrames> grade_saved_frames(worker::WorkerPool& pool, const course::Course& c, const GradeFlags& f,
                                          const course::Checkpoint& checkpoint, const fs::path& root, const course::SavedFrameFiles& files,
                                          const std::optional<std::pair<fs::path, fs::path>>& code) {
  road::FramesSubmission submission{{}, files.missing(c, checkpoint), {}, std::nullopt};
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
  return road::grade_saved_frames(pool, c, checkpoint, std::move(submission), frames_settings(f));
}

worker::PoolConfig pool_config(const GradeFlags& f, int jobs) {
  worker::PoolConfig c;
  const int cores = static_cast<int>(core::usable_cores());  // a grader's cgroup, not the host's cores
  c.workers = f.workers > 0 ? f.workers : std::min(cores, std::max(1, jobs));
  c.llvmpipe_threads = std::max(1, cores / c.workers);
  c.compile_deadline = c.render_deadline = std::chrono::milliseconds(f.timeout_ms);
  c.max_queue = static_cast<size_t>(std::max(jobs, 1));
  c.force_software = f.software;
  c.warm_up = worker::WarmUp::none;  // the jobs are queued at once: a warm-up would only delay the first
  return c;
}

}  // namespace shadelab::cli
