#include "http/problem.h"

#include "worker/job.h"

namespace shadelab::http {

std::string_view title(ErrorCode code) {
  switch (code) {
    case ErrorCode::compile_failed: return "The shader does not compile";
    case ErrorCode::link_failed: return "The shaders do not link";
    case ErrorCode::missing_version: return "The shader does not start with #version 300 es";
    case ErrorCode::compile_timeout: return "The shader took too long to compile";
    case ErrorCode::render_timeout: return "The shader took too long to render";
    case ErrorCode::compile_crashed: return "The graphics driver crashed compiling the shader";
    case ErrorCode::render_crashed: return "The graphics driver crashed rendering the shader";
    case ErrorCode::out_of_memory: return "The render used too much memory";
    case ErrorCode::queue_full: return "The service is busy";
    case ErrorCode::payload_too_large: return "The request is too large";
    case ErrorCode::uniform_type_mismatch: return "A uniform value does not fit its type";
    default: return "The request could not be served";
  }
}

nlohmann::json problem(const Error& e, const std::string& instance) {
  const auto details = worker::to_json(e);
  nlohmann::json p = {{"type", "urn:shadelab:error:" + std::string(to_string(e.code))},
                      {"title", title(e.code)},
                      {"status", http_status(e.code)},
                      {"code", to_string(e.code)},
                      {"detail", e.message},
                      {"instance", instance},
                      {"diagnostics", details["diagnostics"]}};
  if (!e.driver_log.empty()) p["driverLog"] = e.driver_log;
  return p;
}

}  // namespace shadelab::http
