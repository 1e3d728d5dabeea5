#pragma once
// The phases a job moves through in its worker (worker/pool.h): the submission's compile, its
// render, and a grade's own work. The worker announces each as it begins; the pool gives each its
// own budget and, when one is overrun or the worker dies in it, says whose doing it was.
#include <optional>
#include <string_view>

namespace shadelab {

enum class JobPhase {
  compile,  // the submission's shaders: a hang or crash here is the submission's
  render,   // the submission's frames: likewise
  grader,   // the reference, the known mistakes, the comparisons: never charged to the submission
};

std::string_view to_string(JobPhase phase);  // its name on the worker's wire
std::optional<JobPhase> job_phase_named(std::string_view name);

// What the worker was doing in the phase, in words: "compiling", "rendering", ...
std::string_view doing(JobPhase phase);

}  // namespace shadelab
