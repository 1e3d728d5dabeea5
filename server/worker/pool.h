#pragma once
// The HTTP process's side of the render workers: a bounded queue, and per worker slot a manager
// thread that starts the worker process, hands it one job at a time, enforces the compile and
// render deadlines and the memory cap, and kills, reaps and replaces a worker that hangs or dies.
// The HTTP process itself never makes an EGL or GL call.
//
// Deadlines count the worker's CPU time, not the clock on the wall: a job's verdict must not
// depend on how busy the machine was or what else ran beside it. A job moves through phases the
// worker announces: compile (the submission's), render (the submission's frames), and for a grade
// grader (the grader's own renders), each with its own budget; only the first two are the
// submission's, so only they can time it out. A wall-clock cap, a multiple
// of the deadline, is the backstop for a worker that stops using the CPU without answering
// (stopped, or waiting on a hung GPU).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/expected.h"
#include "worker/protocol.h"
#include "worker/worker_main.h"

namespace shadelab::worker {

class ForkServer;

struct PoolConfig {
  int workers = 2;
  std::chrono::milliseconds compile_deadline{10'000};  // CPU time
  std::chrono::milliseconds render_deadline{20'000};   // CPU time
  // A grade's own work after the submission's frames are rendered (the reference, the known
  // mistakes, the comparisons): bounded on its own, and never charged to the submission.
  std::chrono::milliseconds grader_deadline{120'000};  // CPU time
  int wall_clock_factor = 4;                           // wall-clock cap: this many deadlines
  std::chrono::milliseconds start_deadline{15'000};
  size_t max_queue = 64;
  size_t memory_limit_bytes = size_t{2} << 30;  // per worker
  int cpu_limit_seconds = 600;                  // RLIMIT_CPU backstop over a worker's whole life
  int llvmpipe_threads = 1;                     // LP_NUM_THREADS per worker
  // A worker is ready when it holds its EGL context; its warm-up (the built-in course's default job:
  // the mesh parsed and uploaded, the shared vertex shader's JIT, ~250 ms on the 2-core machine at
  // 512 x 512) is drawn right after, and a job that arrives meanwhile waits for it. before_ready:
  // the pool's first workers warm up before they say they are ready (start to /readyz then
  // includes it; replacements still warm up after). none: no worker warms up (worker_main.h).
  WarmUp warm_up = WarmUp::after_ready;
  bool force_software = false;
  std::string executable = "/proc/self/exe";    // started as `<executable> worker`
  // Workers forked from here when set (started before the process's first thread; serve does);
  // fork + exec of `executable` otherwise, or when it fails.
  std::shared_ptr<ForkServer> fork_server;
};

// What became of a job: the worker's answer (worker/result.h reads it), or, when the worker
// never answered (it hung, crashed, ran out of memory, could not start), why.
struct JobResult {
  bool answered = false;
  Message answer;
  Error error{ErrorCode::io_error, "", {}, {}};
  double queue_ms = 0;    // waiting for a worker
  double worker_ms = 0;   // in the worker, from hand-over to result
};

// One worker's memory as the pool last saw it: its resident set now, and the caches its last
// answer reported.
struct WorkerMemory {
  int worker = 0;  // the slot: 0 .. workers - 1 (a replacement keeps its slot)
  std::uint64_t resident_bytes = 0, reference_cache_bytes = 0, cached_programs = 0, cached_meshes = 0;
  std::uint64_t cached_mesh_bytes = 0;  // parsed meshes and their vertex and index buffers
};

struct PoolStats {
  size_t queue_depth = 0;
  std::uint64_t crashes = 0, timeouts = 0, restarts = 0, out_of_memory = 0;
  size_t workers_ready = 0;  // holding a context and waiting for or running a job
  size_t workers = 0;        // configured: the pool is whole when every one is ready
  std::vector<WorkerMemory> memory;  // one per slot
  // The most any worker held while running a job of each kind (its resident set, read every 50 ms
  // of the job and at its answer): which kind of job needs the memory.
  std::map<std::string, std::uint64_t> peak_resident_by_kind;
};

class WorkerPool {
 public:
  explicit WorkerPool(PoolConfig config);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  enum class Lane { normal, retry };
  // A queue_full error when the bounded queue is full (the caller answers 503). A retry goes to
  // the front of the queue: the next worker that comes free takes it, ahead of new work.
  Expected<std::future<JobResult>> submit(Message job, Lane lane = Lane::normal);
  bool ready() const;
  PoolStats stats() const;
  std::string renderer() const;   // GL_RENDERER as the workers report it
  std::vector<int> worker_pids() const;
  const PoolConfig& config() const { return config_; }

 private:
  struct Slot;
  struct Pending {
    Message job;
    std::promise<JobResult> promise;
    std::chrono::steady_clock::time_point queued;
  };
  enum class Popped { job, stopping, worker_gone };
  // The next job; while none comes, `worker_gone` is asked every 50 ms whether the slot's idle
  // worker has died (killed from outside), so the pool replaces it before a job finds it dead.
  Popped pop(Pending& out, const std::function<bool()>& worker_gone);

  PoolConfig config_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Pending> queue_;
  bool stopping_ = false;
  std::string renderer_;
  std::atomic<std::uint64_t> crashes_{0}, timeouts_{0}, restarts_{0}, out_of_memory_{0};
  std::map<std::string, std::uint64_t> peak_resident_by_kind_;  // under mutex_
  std::vector<std::unique_ptr<Slot>> slots_;
};

}  // namespace shadelab::worker
