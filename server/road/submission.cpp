#include "road/submission.h"

#include <chrono>

#include "core/words.h"
#include "grade/catalogue_reading.h"
#include "render/render_request.h"
#include "worker/client.h"
#include "worker/course_job.h"

namespace shadelab::road {

namespace {

double seconds_of(double queue_ms, double worker_ms) { return (queue_ms + worker_ms) / 1000; }

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void note_attempts(grade::Report& report, int attempts, const std::string& retried) {
  report.attempts = attempts;
  if (attempts == 2) report.messages.push_back(retried);
}

// The frames' grade when the set cannot be graded: the problem named, with what the set should be.
FramesGrade unsendable(const course::Course& c, const course::Checkpoint& checkpoint, const FramesSettings& s, const std::string& why,
                       bool with_code) {
  const Error e = make_error(ErrorCode::frames_invalid, why);
  FramesGrade out{{grade::failed_submission(e, checkpoint.name, s.max_score), std::nullopt, {}}, 0};
  out.result.frames.messages.push_back("the deliverable is " + c.saved_frame_range(checkpoint) + ", as the page saves them");
  if (with_code) out.result.code = grade::failed_submission(make_error(ErrorCode::frames_invalid, "not compared: " + why), checkpoint.name, s.max_score);
  return out;
}

// The frames' job: the course's, on its mesh, with the code when there is some.
Expected<worker::Job> frames_job(const course::Course& c, const course::Checkpoint& checkpoint, const FramesSettings& s,
                                 const FramesSubmission& submission, std::string& mesh_bytes) {
  worker::Job job = submission.code ? worker::course_job(c, worker::JobKind::grade_frames, submission.code->first, submission.code->second)
                                    : worker::course_job(c, worker::JobKind::grade_frames);
  if (auto a = worker::attach_course_mesh(c, s.mesh.empty() ? c.default_mesh : s.mesh, job, mesh_bytes); !a) return a.take_error();
  grade::GradeOptions options = c.grade_options(checkpoint);
  options.max_score = s.max_score;
  job.grade = c.frames_grade_spec(checkpoint, options);
  job.grade.reference_store = s.reference_store;
  job.grade.heatmap = s.heatmap;
  if (s.picture) job.grade.picture = *s.picture;
  return job;
}

// A code grade's verdict alone: whether it passes, and what the grader says of any failing
// program (its regions, NaN, one colour, a changed starter constant), without the checkpoint's
// formula or the course's catalogue: the readings a repair search makes needless.
worker::Job verdict_job(const worker::Job& job) {
  worker::Job verdict = job;
  verdict.grade.formula.reset();
  verdict.grade.mistakes.clear();
  verdict.grade.read_values = true;  // where it fails, for the search
  return verdict;
}

}  // namespace

Expected<CodeGrade> grade_unreadable(const Error& error, const std::string& checkpoint, double max_score) {
  if (!info(error.code).submission_caused) return error;
  return CodeGrade{{grade::failed_submission(error, checkpoint, max_score), {}}, 0};
}

Expected<CodeGrade> grade_misread(const Error& field_error, const std::optional<ShaderPair>& code, const std::string& checkpoint,
                                  double max_score, const render::RenderLimits& limits) {
  if (info(field_error.code).submission_caused) return grade_unreadable(field_error, checkpoint, max_score);
  if (!code) return field_error;
  render::RenderRequest sources;
  sources.vertex = code->vertex;
  sources.fragment = code->fragment;
  if (auto checked = render::check_sources(sources, limits); !checked && info(checked.error().code).submission_caused)
    return grade_unreadable(checked.error(), checkpoint, max_score);
  return field_error;
}

grade::Report not_handed_in(const std::string& looked_for, const std::string& checkpoint, double max_score) {
  return grade::failed_submission(make_error(ErrorCode::invalid_argument, looked_for), checkpoint, max_score);
}

namespace {

// A code grade no worker answered (`failed`): its grade by the rule (the submission's 0, or the
// service's Error), with the attempts `stopped` made said and the time since `start`.
Expected<CodeGrade> unanswered(const Error& failed, const grade::GradeSpec& spec, const worker::Attempted<worker::GradeResult>& stopped,
                               std::chrono::steady_clock::time_point start) {
  auto grade = grade_unreadable(failed, spec.reference_name, spec.options.max_score);
  if (grade) {
    note_attempts(grade->result.report, stopped.attempts(), stopped.retried());
    grade->seconds = seconds_since(start);  // the attempts' time: no worker answered
  }
  return grade;
}

// A failing program no repair was confirmed for: graded again whole, the formula and the
// catalogue reading its frames, as with no search. What the search said (`searched`, when it ran)
// is kept in the report: what it tried, and that none passed, or that it could not run.
struct Searched {
  std::optional<grade::RepairSearch> tally;
  std::vector<std::string> warnings;
};

Expected<CodeGrade> explained_after_search(worker::WorkerPool& pool, const worker::Job& job, const CodeSubmission& submission,
                                           const Searched& searched, const worker::Attempted<worker::GradeResult>& verdict,
                                           std::chrono::steady_clock::time_point start) {
  const grade::GradeSpec& spec = job.grade;
  auto b = worker::run_twice_if_stopped<worker::GradeResult>(pool, worker::to_message(job, submission.mesh_bytes));
  const auto& stopped = verdict.attempts() > 1 ? verdict : b;  // a stop in either is said
  if (!b.answered) return unanswered(b.answered.error(), spec, stopped, start);
  grade::Report& report = b.answered->result.report;
  note_attempts(report, stopped.attempts(), stopped.retried());
  report.repair_search = searched.tally;
  report.warnings.insert(report.warnings.end(), searched.warnings.begin(), searched.warnings.end());
  return CodeGrade{std::move(b.answered->result), seconds_since(start)};
}

}  // namespace

Expected<CodeGrade> grade_code(worker::WorkerPool& pool, CodeSubmission submission) {
  worker::Job& job = submission.render;
  job.kind = worker::JobKind::grade;
  job.grade = std::move(submission.spec);
  const grade::GradeSpec& spec = job.grade;
  if (auto sources = render::check_sources(job.request, submission.limits); !sources)
    return grade_unreadable(sources.error(), spec.reference_name, spec.options.max_score);
  const auto start = std::chrono::steady_clock::now();
  const bool searching = submission.repair.candidates > 0;
  // With a search, the first grade is the verdict alone: a failing program's repair explains it
  // (docs/grading.md, "One explainer"), so the formula and the catalogue read only what the
  // search could not repair, in a second grade of the same program.
  auto a = worker::run_twice_if_stopped<worker::GradeResult>(pool, worker::to_message(searching ? verdict_job(job) : job, submission.mesh_bytes));
  if (!a.answered) return unanswered(a.answered.error(), spec, a, start);
  grade::Report& report = a.answered->result.report;
  note_attempts(report, a.attempts(), a.retried());
  // A pass, a compile error, or a failure the grader's own diagnosis names (swapped channels) is
  // the grade as the verdict found it. A changed starter constant is searched on (wants_repair)
  // before the catalogue gives it the course's words.
  const bool repairable = searching && wants_repair(report, spec.starter_constants);
  if (searching) grade::name_catalogued_constants(report, spec, job.request.fragment.text);
  if (!repairable) return CodeGrade{std::move(a.answered->result), seconds_of(a.answered->queue_ms, a.answered->worker_ms)};
  const size_t warned = report.warnings.size();
  search_repair(pool, job, submission.mesh_bytes, submission.repair_shown, submission.vector_words, report, submission.repair,
                submission.classmates, a.answered->result.values.value_or(repair::ValueAgreement{}));
  if (report.repair_search && report.repair_search->found) return CodeGrade{std::move(a.answered->result), seconds_since(start)};
  const Searched searched{report.repair_search, {report.warnings.begin() + static_cast<std::ptrdiff_t>(warned), report.warnings.end()}};
  return explained_after_search(pool, job, submission, searched, a, start);
}

bool second_search_has_candidates(const CodeSubmission& submission) {
  worker::Job job = submission.render;
  job.grade = submission.spec;
  return class_offers_edits(job, submission.classmates, submission.repair);
}

int full_renders(const grade::Report& report) {
  if (report.frames.empty()) return 0;
  const auto& search = report.repair_search;
  return report.attempts + (search ? search->confirmations + (search->found ? 0 : 1) : 0);
}

Expected<FramesGrade> grade_saved_frames(worker::WorkerPool& pool, const course::Course& c, const course::Checkpoint& checkpoint,
                                   FramesSubmission submission, const FramesSettings& s) {
  const bool with_code = submission.code.has_value();
  if (!submission.missing.empty())
    return unsendable(c, checkpoint, s, and_list(submission.missing) + (submission.missing.size() == 1 ? " is" : " are") + " missing",
                      with_code);
  if (!submission.unreadable.empty()) return unsendable(c, checkpoint, s, submission.unreadable, with_code);
  worker::FramesPayload payload{{}, std::move(submission.saved)};
  auto job = frames_job(c, checkpoint, s, submission, payload.mesh);
  if (!job) return job.take_error();
  if (with_code)
    if (auto sources = render::check_sources(job->request, s.limits); !sources) {
      if (!info(sources.error().code).submission_caused) return sources.take_error();
      // Code that cannot be sent is the code's grade; the frames are graded without it.
      auto without = grade_saved_frames(pool, c, checkpoint, {std::move(payload.saved), {}, {}, std::nullopt}, s);
      if (without) without->result.code = grade::failed_submission(sources.error(), checkpoint.name, s.max_score);
      return without;
    }
  auto a = worker::run_twice_if_stopped<worker::FramesGradeResult>(pool, worker::to_message(*job, payload));
  if (a.answered) {
    if (a.answered->result.code) note_attempts(*a.answered->result.code, a.attempts(), a.retried());
    return FramesGrade{std::move(a.answered->result), seconds_of(a.answered->queue_ms, a.answered->worker_ms)};
  }
  const Error e = a.answered.error();
  if (!info(e.code).submission_caused) return e;
  if (!with_code) return unsendable(c, checkpoint, s, e.message, false);
  // Only the code can hang or crash a worker (the frames are decoded and compared by the grader):
  // the frames are graded again without it, and the code's grade is the failure.
  worker::Job frames_only = *job;
  frames_only.request.vertex = {};
  frames_only.request.fragment = {};
  auto again = worker::run<worker::FramesGradeResult>(pool, worker::to_message(frames_only, payload), worker::WorkerPool::Lane::retry);
  if (!again) {
    if (!info(again.error().code).submission_caused) return again.take_error();
    return unsendable(c, checkpoint, s, again.error().message, with_code);
  }
  again->result.code = grade::failed_submission(e, checkpoint.name, s.max_score);
  note_attempts(*again->result.code, a.attempts(), a.retried());
  return FramesGrade{std::move(again->result), seconds_of(again->queue_ms, again->worker_ms)};
}

}  // namespace shadelab::road
