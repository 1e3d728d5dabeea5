#include "worker/client.h"

namespace shadelab::worker {

namespace {

// A timeout might be the machine's doing and a lost worker (stopped, dropped its socket) is never
// the shader's: both are tried once more before they count.
bool worth_a_second_try(const Error& e) {
  return e.code == ErrorCode::compile_timeout || e.code == ErrorCode::render_timeout || e.code == ErrorCode::worker_lost;
}

}  // namespace

Expected<Answered<GradeResult>> grade(WorkerPool& pool, const Job& job, std::string mesh_bytes) {
  const auto start = std::chrono::steady_clock::now();
  auto graded = run<GradeResult>(pool, to_message(job, mesh_bytes));
  // Retried once, ahead of the queue, on a fresh worker (the one that failed was killed): a grade
  // of 0 for a timeout needs the same verdict twice.
  std::string first_failure;
  if (!graded && worth_a_second_try(graded.error())) {
    first_failure = graded.error().message;
    graded = run<GradeResult>(pool, to_message(job, std::move(mesh_bytes)), WorkerPool::Lane::retry);
  }
  const int attempts = first_failure.empty() ? 1 : 2;
  const std::string retried = "the first attempt was stopped (" + first_failure + ") and the submission was graded again";
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
