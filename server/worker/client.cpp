#include "worker/client.h"

namespace shadelab::worker {

Expected<Answered<GradeResult>> grade(WorkerPool& pool, const Job& job, std::string mesh_bytes) {
  const auto start = std::chrono::steady_clock::now();
  auto graded = run<GradeResult>(pool, to_message(job, std::move(mesh_bytes)));
  if (graded) return graded;
  const Error& e = graded.error();
  if (!info(e.code).submission_caused) return graded.take_error();
  Answered<GradeResult> failed{{grade::failed_submission(e, job.grade.reference_name, job.grade.options.max_score), {}}, 0, 0};
  failed.worker_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return failed;
}

}  // namespace shadelab::worker
