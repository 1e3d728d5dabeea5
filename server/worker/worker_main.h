#pragma once
// The render worker process: one EGL context, warm programs and meshes, one job at a time from
// the HTTP process over `fd`. It may crash or hang on a hostile shader; the pool kills and
// replaces it, which is the point of running it as its own process.
#include "egl/headless_context.h"

namespace shadelab::worker {

// When a worker draws its warm-up job (worker_main.cpp): before it says it is ready, at the
// pool's start, so no client pays it; after, for a replacement, so the pool is whole again in
// milliseconds and only a job that arrives at once waits for the rest of it; never, for a command
// whose jobs are there at once (the CLI's grades), where it would only delay the first by
// rendering a job nobody asked for.
enum class WarmUp { before_ready, after_ready, none };

int run_worker(int fd, const egl::ContextOptions& options, WarmUp warm_up = WarmUp::before_ready);

}  // namespace shadelab::worker
