#pragma once
// Typed jobs through the pool: send a job, wait for the worker, read its typed answer. The HTTP
// routes and the CLI call these and read fields; neither sees a worker's JSON.
#include <string>

#include "core/expected.h"
#include "worker/job.h"
#include "worker/pool.h"
#include "worker/result.h"

namespace shadelab::worker {

template <class Result>
struct Answered {
  Result result;
  double queue_ms = 0;   // waiting for a worker
  double worker_ms = 0;  // in the worker
};

// An Error when the pool is full, the worker hung, crashed or ran out of memory, or the worker
// answered with one.
template <class Result>
Expected<Answered<Result>> run(WorkerPool& pool, Message job, WorkerPool::Lane lane = WorkerPool::Lane::normal) {
  auto future = pool.submit(std::move(job), lane);
  if (!future) return future.take_error();
  JobResult done = future->get();
  if (!done.answered) return std::move(done.error);
  auto result = result_from<Result>(done.answer);
  if (!result) return result.take_error();
  return Answered<Result>{std::move(*result), done.queue_ms, done.worker_ms};
}

// Grading's rule: whatever the submission causes (it does not compile, hangs, crashes the driver:
// ErrorCodeInfo::submission_caused) is its grade, score 0 and the reason; an Error is only what
// the service itself could not do (queue full, no worker, the reference does not render). A
// submission that runs out of time is graded once more before its 0 stands (report.attempts).
Expected<Answered<GradeResult>> grade(WorkerPool& pool, const Job& job, std::string mesh_bytes);

// Saved frames graded (a grade_frames job), by the same rule. The code handed in with them can
// hang or crash its render: that is the code's grade, and the frames are graded again without it.
Expected<Answered<FramesGradeResult>> grade_frames(WorkerPool& pool, const Job& job, const FramesPayload& payload);

}  // namespace shadelab::worker
