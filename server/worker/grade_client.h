#pragma once
// Grading a submission through the worker pool. Whatever happens to the submission (it does not
// compile, hangs, crashes the driver) the answer is a graded result: score 0 and the reason.
#include <nlohmann/json.hpp>

#include "worker/job.h"
#include "worker/pool.h"

namespace shadelab::worker {

struct GradeOutcome {
  nlohmann::json result;   // grade::to_json or grade::failed_submission shape
  std::string heatmap_png; // base64, when the submission rendered
  double seconds = 0;
  std::optional<Error> service_error;  // the service itself could not take the job (queue full, ...)
};

GradeOutcome grade_with_pool(WorkerPool& pool, const Job& job, const std::string& mesh_payload);

}  // namespace shadelab::worker
