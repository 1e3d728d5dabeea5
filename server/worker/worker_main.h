#pragma once
// The render worker process: one EGL context, warm programs and meshes, one job at a time from
// the HTTP process over `fd`. It may crash or hang on a hostile shader; the pool kills and
// replaces it, which is the point of running it as its own process.
#include "egl/headless_context.h"

namespace shadelab::worker {

int run_worker(int fd, const egl::ContextOptions& options);

}  // namespace shadelab::worker
