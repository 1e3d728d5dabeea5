#include "core/error.h"

namespace shadelab {

namespace {
struct CodeInfo {
  ErrorCode code;
  std::string_view name;
  int status;
};

// The contract, as a table. Statuses follow RFC 9110: 400 for requests we cannot read,
// 422 for well-formed requests whose content (a shader, a mesh) we cannot use.
constexpr CodeInfo kCodes[] = {
    {ErrorCode::invalid_argument, "invalid_argument", 400},
    {ErrorCode::unknown_preset, "unknown_preset", 404},
    {ErrorCode::shader_source_invalid, "shader_source_invalid", 422},
    {ErrorCode::missing_version, "missing_version", 422},
    {ErrorCode::compile_failed, "compile_failed", 422},
    {ErrorCode::link_failed, "link_failed", 422},
    {ErrorCode::uniform_type_mismatch, "uniform_type_mismatch", 422},
    {ErrorCode::mesh_not_found, "mesh_not_found", 404},
    {ErrorCode::mesh_parse_failed, "mesh_parse_failed", 422},
    {ErrorCode::mesh_invalid, "mesh_invalid", 422},
    {ErrorCode::mesh_empty, "mesh_empty", 422},
    {ErrorCode::mesh_too_large, "mesh_too_large", 413},
    {ErrorCode::msaa_unsupported, "msaa_unsupported", 422},
    {ErrorCode::egl_unavailable, "egl_unavailable", 503},
    {ErrorCode::gl_error, "gl_error", 500},
    {ErrorCode::io_error, "io_error", 500},
    {ErrorCode::queue_full, "queue_full", 503},
    {ErrorCode::compile_timeout, "compile_timeout", 422},
    {ErrorCode::render_timeout, "render_timeout", 422},
    {ErrorCode::compile_crashed, "compile_crashed", 422},
    {ErrorCode::render_crashed, "render_crashed", 422},
    {ErrorCode::out_of_memory, "out_of_memory", 422},
    {ErrorCode::not_ready, "not_ready", 503},
    {ErrorCode::payload_too_large, "payload_too_large", 413},
    {ErrorCode::not_found, "not_found", 404},
    {ErrorCode::worker_protocol, "worker_protocol", 500},
    {ErrorCode::view_transform_unavailable, "view_transform_unavailable", 503},
};

const CodeInfo& info(ErrorCode code) {
  for (const auto& entry : kCodes)
    if (entry.code == code) return entry;
  return kCodes[0];  // unreachable: every enumerator has a row (checked by a test)
}
}  // namespace

std::string_view to_string(ErrorCode code) { return info(code).name; }
int http_status(ErrorCode code) { return info(code).status; }

std::string Diagnostic::format() const {
  std::string out = file.empty() ? std::string(stage) : file;
  if (line > 0) {
    out += ':' + std::to_string(line);
    if (column > 0) out += ':' + std::to_string(column);
  }
  out += ": " + severity + ": " + message;
  return out;
}

std::string Error::format() const {
  std::string out = std::string(to_string(code)) + ": " + message;
  for (const auto& d : diagnostics) out += "\n" + d.format();
  return out;
}

}  // namespace shadelab
