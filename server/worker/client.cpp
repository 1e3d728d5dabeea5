#include "worker/client.h"

namespace shadelab::worker {

namespace {

// A timeout might be the machine's doing and a lost worker (stopped, dropped its socket) is never
// the shader's: both are tried once more before they count.
bool worth_a_second_try(const Error& e) {
  return e.code == ErrorCode::compile_timeout || e.code == ErrorCode::render_timeout || e.code == ErrorCode::worker_lost;
}

template <class Result>
struct Attempted {
  Expected<Answered<Result>> answered;
  std::string first_failure;  // empty when the first attempt stood
  int attempts() const { return first_failure.empty() ? 1 : 2; }
  std::string retried() const { return "the first attempt was stopped (" + first_failure + ") and the submission was graded again"; }
};

// Retried once, ahead of the queue, on a fresh worker (the one that failed was killed): a grade
// of 0 for a timeout needs the same verdict twice.
template <class Result>
Attempted<Result> run_twice_if_stopped(WorkerPool& pool, const Message& job) {
  Attempted<Result> a{run<Result>(pool, job), {}};
  if (!a.answered && worth_a_second_try(a.answered.error())) {
    a.first_failure = a.answered.error().message;
    a.answered = run<Result>(pool, job, WorkerPool::Lane::retry);
  }
  return a;
}

template <class Result>
void note_attempts(grade::Report& report, const Attempted<Result>& a) {
  report.attempts = a.attempts();
  if (a.attempts() == 2) report.messages.push_back(a.retried());
}

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Expected<Answered<GradeResult>> grade(WorkerPool& pool, const Job& job, std::string mesh_bytes) {
  const auto start = std::chrono::steady_clock::now();
  auto a = run_twice_if_stopped<GradeResult>(pool, to_message(job, std::move(mesh_bytes)));
  if (a.answered) {
    note_attempts(a.answered->result.report, a);
    return std::move(a.answered);
  }
  const Error& e = a.answered.error();
  if (!info(e.code).submission_caused) return a.answered.take_error();
  Answered<GradeResult> failed{{grade::failed_submission(e, job.grade.reference_name, job.grade.options.max_score), {}}, 0, ms_since(start)};
  note_attempts(failed.result.report, a);
  return failed;
}

Expected<Answered<FramesGradeResult>> grade_frames(WorkerPool& pool, const Job& job, const FramesPayload& payload) {
  auto a = run_twice_if_stopped<FramesGradeResult>(pool, to_message(job, payload));
  if (a.answered) {
    if (a.answered->result.code) note_attempts(*a.answered->result.code, a);
    return std::move(a.answered);
  }
  const Error e = a.answered.error();
  if (!info(e.code).submission_caused) return a.answered.take_error();
  // Only the code can hang or crash a worker (the frames are decoded and compared by the grader):
  // the frames are graded again without it, and the code's grade is the failure.
  Job frames_only = job;
  frames_only.request.vertex = {};
  frames_only.request.fragment = {};
  auto again = run<FramesGradeResult>(pool, to_message(frames_only, payload), WorkerPool::Lane::retry);
  if (!again) return again.take_error();
  again->result.code = grade::failed_submission(e, job.grade.reference_name, job.grade.options.max_score);
  note_attempts(*again->result.code, a);
  return again;
}

}  // namespace shadelab::worker
