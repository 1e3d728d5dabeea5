#pragma once
// A command run through the shell with its stdout and stderr together: what the tests of the
// shadelab executable (and the tools it is checked with: pdftotext, python3) read answers from.
#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace shadelab::testkit {

struct CommandRun {
  int status = -1;     // the exit status; -1 when it did not exit normally
  std::string output;  // stdout and stderr
};

inline CommandRun run_command(const std::string& command) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  CommandRun run;
  if (!pipe) return run;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) run.output.append(buf, n);
  const int status = pclose(pipe);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

// `shadelab ARGS`, the binary this build made.
inline CommandRun run_shadelab(const std::string& args) { return run_command(std::string(SHADELAB_CLI) + " " + args); }

}  // namespace shadelab::testkit
