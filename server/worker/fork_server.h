#pragma once
// A fork server (Android's zygote, Chromium's zygote): a process forked from the server before
// the server starts any thread, with every library already loaded, which forks render workers on
// request. A worker started from it skips exec, the dynamic loader and Mesa's driver load, so
// replacing a worker killed by a hostile shader costs a fork and an EGL context.
//
// The workers stay the server's own children: each is forked through a short-lived intermediate
// that exits at once, and the server is their subreaper (PR_SET_CHILD_SUBREAPER), so the pool
// waits for them and reads how they died exactly as for a worker it forked itself.
#include <sys/types.h>

#include <memory>
#include <mutex>

#include "core/expected.h"
#include "worker/worker_main.h"

namespace shadelab::worker {

// What a worker starts with: the same as `shadelab worker` gets on its command line and
// environment when the pool execs it.
struct WorkerLaunch {
  int llvmpipe_threads = 1;
  bool force_software = false;
  int cpu_limit_seconds = 600;
  WarmUp warm_up = WarmUp::before_ready;
};

class ForkServer {
 public:
  // Forks the fork server. An error once this process has started a thread of its own: a fork
  // copies only the calling thread, and a lock another thread held would stay locked in the copy.
  static Expected<std::shared_ptr<ForkServer>> start();
  ~ForkServer();  // the fork server sees its socket close and exits; it is reaped here
  ForkServer(const ForkServer&) = delete;
  ForkServer& operator=(const ForkServer&) = delete;

  // Starts a worker serving `worker_fd` (its end of a socketpair; the caller still closes its own
  // copy). Returns the worker's pid, a child of this process.
  Expected<pid_t> spawn(int worker_fd, const WorkerLaunch& launch);

 private:
  ForkServer(int socket, pid_t pid) : socket_(socket), pid_(pid) {}
  std::mutex mutex_;  // one request at a time: each pool slot spawns from its own thread
  int socket_;
  pid_t pid_;
};

}  // namespace shadelab::worker
