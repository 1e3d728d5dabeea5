#include "worker/fatal_signal.h"

#include <execinfo.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>

namespace shadelab::worker {

namespace {

// Written by the serving thread between jobs and phases, read by the handler on the same thread.
char doing[160] = "idle";

void say(const char* text) { (void)!::write(STDERR_FILENO, text, std::strlen(text)); }

void on_fatal(int signal) {
  say("shadelab worker: fatal signal ");
  say(sigabbrev_np(signal) ? sigabbrev_np(signal) : "?");
  say(" while ");
  say(doing);
  say("; its stack:\n");
  void* frames[48];
  ::backtrace_symbols_fd(frames, ::backtrace(frames, 48), STDERR_FILENO);
  ::signal(signal, SIG_DFL);
  ::raise(signal);
}

}  // namespace

void report_fatal_signals() {
  void* warm[1];
  (void)::backtrace(warm, 1);  // loads libgcc now: its first call may allocate, which a handler must not
  struct sigaction action {};
  action.sa_handler = on_fatal;
  action.sa_flags = SA_RESETHAND;
  sigemptyset(&action.sa_mask);
  for (int s : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT}) ::sigaction(s, &action, nullptr);
}

void note_doing(std::string_view what) {
  const size_t n = std::min(what.size(), sizeof doing - 1);
  std::memcpy(doing, what.data(), n);
  doing[n] = '\0';
}

}  // namespace shadelab::worker
