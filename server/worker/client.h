#pragma once
// Typed jobs through the pool: send a job, wait for the worker, read its typed answer. Transport
// only: what an answer or an error means for a grade is road/submission.h's to say.
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

// A job run once more, ahead of the queue on a fresh worker, when its first attempt was stopped
// (a timeout), its worker was lost, or the grader's own renders failed: each may be the machine's
// or the grader's doing, so none counts against the submission until it happens twice.
template <class Result>
struct Attempted {
  Expected<Answered<Result>> answered;
  std::string first_failure;  // why the first attempt was stopped; empty when it stood
  int attempts() const { return first_failure.empty() ? 1 : 2; }
  std::string retried() const { return "the first attempt was stopped (" + first_failure + ") and the submission was graded again"; }
};

bool worth_a_second_try(const Error& e);

template <class Result>
Attempted<Result> run_twice_if_stopped(WorkerPool& pool, const Message& job) {
  Attempted<Result> a{run<Result>(pool, job), {}};
  if (!a.answered && worth_a_second_try(a.answered.error())) {
    a.first_failure = a.answered.error().message;
    a.answered = run<Result>(pool, job, WorkerPool::Lane::retry);
  }
  return a;
}

}  // namespace shadelab::worker
