#include "worker/client.h"

namespace shadelab::worker {

namespace {

bool timed_out(const Error& e) { return e.code == ErrorCode::compile_timeout || e.code == ErrorCode::render_timeout; }

}  // namespace

Expected<Answered<GradeResult>> grade(WorkerPool& pool, const Job& job, std::string mesh_bytes) {
  const auto start = std::chrono::steady_clock::now();
  auto graded = run<GradeResult>(pool, to_message(job, mesh_bytes));
  // A timeout is retried once, ahead of the queue, on a fresh worker (the one that ran out of
  // time was killed): a grade of 0 needs the same verdict twice.
  std::string first_timeout;
  if (!graded && timed_out(graded.error())) {
    first_timeout = graded.error().message;
    graded = run<GradeResult>(pool, to_message(job, std::move(mesh_bytes)), WorkerPool::Lane::retry);
  }
  const int attempts = first_timeout.empty() ? 1 : 2;
  const std::string retried = "the first attempt was stopped (" + first_timeout + ") and the submission was graded again";
  if (graded) {
    graded->result.report.attempts = attempts;
    if (attempts == 2) graded->result.report.messages.push_back(retried);
    return graded;
  }
  const Error& e = graded.error();
  if (!info(e.code).submission_caused) return graded.take_error();
  Answered<GradeResult> failed{{grade::failed_submission(e, job.grade.reference_name, job.grade.options.max_score), {}}, 0, 0};
  failed.result.report.attempts = attempts;
  if (attempts == 2) failed.result.report.messages.push_back(retried);
  failed.worker_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return failed;
}

}  // namespace shadelab::worker
