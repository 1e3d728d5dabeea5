#pragma once
// Starting one render worker process, the one place that knows how: through the pool's fork
// server when it has one (milliseconds), else fork + exec of `<executable> worker --fd 3`.
#include <sys/types.h>

#include "core/expected.h"
#include "worker/pool.h"

namespace shadelab::worker {

// A worker serving `child_fd`, its end of a socketpair (the caller closes its own copy). The
// worker is a child of this process either way.
// `warm_up`: when it draws its warm-up job (worker_main.h).
Expected<pid_t> launch_worker(const PoolConfig& config, int child_fd, WarmUp warm_up);

// The limits every worker runs under, set in the new process (async-signal-safe): its CPU time
// (a backstop over its whole life), 64 open files, and 4096 processes for the user, which
// llvmpipe's threads count against: room enough for them, too few for a fork bomb should student
// code ever execute. Root is exempt from the last.
void apply_worker_limits(int cpu_limit_seconds);

}  // namespace shadelab::worker
