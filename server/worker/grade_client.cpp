#include "worker/grade_client.h"

#include <chrono>

#include "grade/report.h"

namespace shadelab::worker {

GradeOutcome grade_with_pool(WorkerPool& pool, const Job& job, const std::string& mesh_payload) {
  GradeOutcome out;
  const auto start = std::chrono::steady_clock::now();
  auto future = pool.submit({to_json(job), mesh_payload});
  if (!future) {
    out.service_error = future.error();
    return out;
  }
  JobResult r = future->get();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!r.ok) {
    switch (r.error.code) {
      // What a submission can cause is its grade; anything else is the service's problem.
      case ErrorCode::compile_timeout: case ErrorCode::render_timeout: case ErrorCode::compile_crashed:
      case ErrorCode::render_crashed: case ErrorCode::out_of_memory: case ErrorCode::compile_failed:
      case ErrorCode::link_failed: case ErrorCode::shader_source_invalid: case ErrorCode::missing_version:
      case ErrorCode::uniform_type_mismatch:
        out.result = grade::failed_submission(r.error, job.grade.reference_name, job.grade.options.max_score);
        break;
      default:
        out.service_error = r.error;
    }
    return out;
  }
  out.result = r.header.value("result", nlohmann::json::object());
  if (out.result.contains("heatmap")) {
    out.heatmap_png = out.result["heatmap"];
    out.result.erase("heatmap");
  }
  return out;
}

}  // namespace shadelab::worker
