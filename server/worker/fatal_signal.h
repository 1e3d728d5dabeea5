#pragma once
// A worker that dies of a signal (a driver's crash) says so on stderr before it goes: which
// signal, during which job and phase, and the native stack, so an operator has more than "the
// worker crashed" to report upstream. The signal is then delivered as before (the default action:
// the server reads the death from the exit status, worker/pool.cpp). Async-signal-safe: the
// handler only formats into fixed buffers and calls write(2) and backtrace_symbols_fd(3).
#include <string_view>

namespace shadelab::worker {

// Installs the reporter for SIGSEGV, SIGBUS, SIGILL, SIGFPE and SIGABRT.
void report_fatal_signals();

// What the worker is doing, for the report: "grade, rendering the grader's references".
void note_doing(std::string_view what);

}  // namespace shadelab::worker
