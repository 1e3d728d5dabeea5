#include "worker/frames_job.h"

#include "core/words.h"
#include "grade/report.h"
#include "render/render_request.h"
#include "worker/course_job.h"

namespace shadelab::worker {

namespace {

// The frames' grade when the set cannot be graded: the problem named, with what the set should be.
GradedFrames unsendable(const course::Course& c, const course::Checkpoint& checkpoint, const FramesGradeSettings& s, const std::string& why,
                        bool with_code) {
  const Error e = make_error(ErrorCode::frames_invalid, why);
  GradedFrames out{{grade::failed_submission(e, checkpoint.name, s.max_score), std::nullopt, {}}, 0};
  out.result.frames.messages.push_back("the deliverable is " + c.frame_file(checkpoint.prefix, 0, "png") + " to " +
                                       c.frame_file(checkpoint.prefix, c.frames - 1, "png") + ", as the page saves them");
  if (with_code)
    out.result.code = grade::failed_submission(make_error(ErrorCode::frames_invalid, "not compared: " + why), checkpoint.name, s.max_score);
  return out;
}

}  // namespace

Expected<GradedFrames> grade_frame_set(WorkerPool& pool, const course::Course& c, const course::Checkpoint& checkpoint,
                                       FramesSubmission submission, const FramesGradeSettings& s) {
  const bool with_code = submission.code.has_value();
  if (!submission.missing.empty())
    return unsendable(c, checkpoint, s, and_list(submission.missing) + (submission.missing.size() == 1 ? " is" : " are") + " missing",
                      with_code);
  if (!submission.unreadable.empty()) return unsendable(c, checkpoint, s, submission.unreadable, with_code);
  grade::GradeOptions options;
  options.max_score = s.max_score;
  Job job = course_job(c, JobKind::grade_frames);
  FramesPayload payload{{}, std::move(submission.saved)};
  if (auto a = attach_course_mesh(c, s.mesh.empty() ? c.default_mesh : s.mesh, job, payload.mesh); !a) return a.take_error();
  job.grade = c.frames_grade_spec(checkpoint, options);
  job.grade.reference_store = s.reference_store;
  job.grade.heatmap = s.heatmap;
  job.request = with_code ? c.render_request(submission.code->first, submission.code->second) : c.render_request({}, {});
  if (with_code)
    if (auto sources = render::check_sources(job.request, render::RenderLimits{}); !sources) {
      if (!info(sources.error().code).submission_caused) return sources.take_error();
      // Code that cannot be sent is the code's grade; the frames are graded without it.
      auto without = grade_frame_set(pool, c, checkpoint, {std::move(payload.saved), {}, {}, std::nullopt}, s);
      if (without) without->result.code = grade::failed_submission(sources.error(), checkpoint.name, s.max_score);
      return without;
    }
  auto answered = grade_frames(pool, job, payload);
  if (!answered) {
    if (!info(answered.error().code).submission_caused) return answered.take_error();
    return unsendable(c, checkpoint, s, answered.error().message, with_code);
  }
  return GradedFrames{std::move(answered->result), (answered->queue_ms + answered->worker_ms) / 1000};
}

}  // namespace shadelab::worker
