#pragma once
// Faults a worker injects into itself, for the fault-injection tests and bench (tests/fault_test.cpp,
// bench/fault_bench.cpp, docs/reliability.md): never active unless the server was started with
// SHADELAB_FAULT_INJECTION=<log file> in its environment (the workers inherit it). A render job
// then names its fault in its fragment shader, an uploaded mesh in an OBJ comment, on a line of
// its own:
//
//   // shadelab-fault: <phase> <action> [anything, e.g. a serial number that defeats caches]
//   # shadelab-fault: mesh <action>
//
// | phase    | where the worker is                                                    |
// |----------|------------------------------------------------------------------------|
// | compile  | the job read, nothing compiled                                         |
// | render   | compiled, the server told the render phase began                       |
// | readback | frame 0's pixels read back (in the frame sink)                         |
// | encode   | every frame rendered, the output not yet encoded                       |
// | mesh     | an uploaded mesh's bytes received, not yet parsed (its check job)      |
// | grader   | a grade's own work begun: its references not yet rendered              |
// | start    | a worker started, its ready message not yet sent: named by the         |
// |          | environment, SHADELAB_FAULT_AT_START=<action>, for every worker        |
//
// | action   | what the worker does                                                   |
// |----------|------------------------------------------------------------------------|
// | kill     | SIGKILL to itself                                                      |
// | crash    | SIGSEGV to itself (a driver's crash)                                   |
// | stop     | SIGSTOP to itself (stops answering, uses no CPU)                       |
// | close    | closes its socket and waits forever                                    |
// | garbage  | sends a well-framed message whose header is not JSON, then goes on     |
// | noise    | sends 64 bytes that are no message header, then goes on                |
// | truncate | sends the start of a message and exits                                 |
// | hog      | allocates and touches memory until it is stopped                       |
//
// Before acting the worker appends "<phase> <action> <steady-clock ns>" to the log file, so a
// test can time the recovery from the moment of the fault.
#include <string>
#include <string_view>

namespace shadelab::worker {

enum class FaultPhase { compile, render, readback, encode, mesh, grader, start };

struct FaultPlan {
  bool active = false;
  FaultPhase phase = FaultPhase::compile;
  std::string action;
};

// The fault a job's fragment source (or a mesh file) asks for; inactive without
// SHADELAB_FAULT_INJECTION.
FaultPlan fault_plan(std::string_view text);

// The fault every worker injects as it starts (SHADELAB_FAULT_AT_START); inactive without
// SHADELAB_FAULT_INJECTION.
FaultPlan start_fault_plan();

// Injects the plan's fault if `phase` is its phase; `socket` is the worker's end of its socket.
void inject_fault(const FaultPlan& plan, FaultPhase phase, int socket);

}  // namespace shadelab::worker
