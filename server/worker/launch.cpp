#include "worker/launch.h"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "worker/fork_server.h"

namespace shadelab::worker {

namespace {

Expected<pid_t> fork_and_exec(const PoolConfig& c, int child_fd, WarmUp warm_up) {
  // Everything the child needs is prepared before fork: after it, only async-signal-safe calls.
  std::vector<std::string> args = {c.executable, "worker", "--fd", "3"};
  if (c.force_software) args.push_back("--software");
  if (warm_up == WarmUp::after_ready) args.push_back("--warm-after-ready");
  if (warm_up == WarmUp::none) args.push_back("--no-warm-up");
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, "LP_NUM_THREADS=", 15) != 0) env.emplace_back(*e);
  env.push_back("LP_NUM_THREADS=" + std::to_string(c.llvmpipe_threads));
  std::vector<char*> argv, envp;
  for (auto& a : args) argv.push_back(a.data());
  for (auto& e : env) envp.push_back(e.data());
  argv.push_back(nullptr);
  envp.push_back(nullptr);

  const pid_t child = ::fork();
  if (child < 0) return make_error(ErrorCode::not_ready, std::string("fork: ") + std::strerror(errno));
  if (child == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlive the server
    ::dup2(child_fd, 3);                  // dup2 clears close-on-exec on fd 3
    apply_worker_limits(c.cpu_limit_seconds);
    ::execve(argv[0], argv.data(), envp.data());
    ::_exit(127);
  }
  return child;
}

}  // namespace

void apply_worker_limits(int cpu_limit_seconds) {
  const rlimit cpu{static_cast<rlim_t>(cpu_limit_seconds), static_cast<rlim_t>(cpu_limit_seconds + 5)};
  const rlimit files{64, 64};
  const rlimit processes{4096, 4096};
  ::setrlimit(RLIMIT_CPU, &cpu);
  ::setrlimit(RLIMIT_NOFILE, &files);
  ::setrlimit(RLIMIT_NPROC, &processes);
}

Expected<pid_t> launch_worker(const PoolConfig& c, int child_fd, WarmUp warm_up) {
  if (c.fork_server) {
    auto forked = c.fork_server->spawn(child_fd, {c.llvmpipe_threads, c.force_software, c.cpu_limit_seconds, warm_up});
    if (forked) return forked;
    // Still serve: the fork server only saves time. Said once per failure, to the operator.
    std::cerr << "shadelab: " << forked.error().message << "; starting the worker with fork + exec\n";
  }
  return fork_and_exec(c, child_fd, warm_up);
}

}  // namespace shadelab::worker
