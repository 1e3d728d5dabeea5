#include "core/error.h"

#include "core/check.h"

namespace shadelab {

namespace {
// The contract, as a table. Statuses follow RFC 9110: 400 for requests we cannot read, 422 for
// well-formed requests whose content (a shader, a mesh) we cannot use. Timeouts, crashes and
// memory kills are 422 too: they are properties of the submitted shader, and resending it gives
// the same answer. "submission" marks what a student's shaders can cause: grading scores those 0
// with the reason; anything else is the service's problem and is reported as such.
constexpr ErrorCodeInfo kCodes[] = {
    // code                                  name                          status title                                                   submission retry
    {ErrorCode::invalid_argument,           "invalid_argument",           400, "The request is not valid",                              false, false},
    {ErrorCode::unknown_preset,             "unknown_preset",             404, "No such preset or checkpoint",                          false, false},
    {ErrorCode::shader_source_invalid,      "shader_source_invalid",      422, "The shader source cannot be read",                      true,  false},
    {ErrorCode::missing_version,            "missing_version",            422, "The shader does not start with #version 300 es",        true,  false},
    {ErrorCode::compile_failed,             "compile_failed",             422, "The shader does not compile",                           true,  false},
    {ErrorCode::link_failed,                "link_failed",                422, "The shaders do not link",                               true,  false},
    {ErrorCode::uniform_type_mismatch,      "uniform_type_mismatch",      422, "A uniform value does not fit its type",                 true,  false},
    {ErrorCode::mesh_not_found,             "mesh_not_found",             404, "No such mesh",                                          false, false},
    {ErrorCode::mesh_parse_failed,          "mesh_parse_failed",          422, "The mesh file cannot be read",                          false, false},
    {ErrorCode::mesh_invalid,               "mesh_invalid",               422, "The mesh holds invalid data",                           false, false},
    {ErrorCode::mesh_empty,                 "mesh_empty",                 422, "The mesh has no triangles",                             false, false},
    {ErrorCode::mesh_too_large,             "mesh_too_large",             413, "The mesh has too many triangles",                       false, false},
    {ErrorCode::msaa_unsupported,           "msaa_unsupported",           422, "The renderer does not offer that many samples",         false, false},
    {ErrorCode::egl_unavailable,            "egl_unavailable",            503, "No graphics device is available",                       false, false},
    {ErrorCode::gl_error,                   "gl_error",                   500, "The graphics driver reported an error",                 false, false},
    {ErrorCode::io_error,                   "io_error",                   500, "The request could not be served",                       false, false},
    {ErrorCode::queue_full,                 "queue_full",                 503, "The service is busy",                                   false, true},
    {ErrorCode::compile_timeout,            "compile_timeout",            422, "The shader took too long to compile",                   true,  false},
    {ErrorCode::render_timeout,             "render_timeout",             422, "The shader took too long to render",                    true,  false},
    {ErrorCode::compile_crashed,            "compile_crashed",            422, "The graphics driver crashed compiling the shader",      true,  false},
    {ErrorCode::render_crashed,             "render_crashed",             422, "The graphics driver crashed rendering the shader",      true,  false},
    {ErrorCode::out_of_memory,              "out_of_memory",              422, "The render used too much memory",                       true,  false},
    {ErrorCode::not_ready,                  "not_ready",                  503, "The service is not ready",                              false, true},
    {ErrorCode::payload_too_large,          "payload_too_large",          413, "The request is too large",                              false, false},
    {ErrorCode::not_found,                  "not_found",                  404, "No such resource",                                      false, false},
    {ErrorCode::worker_protocol,            "worker_protocol",            500, "A render worker answered something unreadable",         false, false},
    {ErrorCode::view_transform_unavailable, "view_transform_unavailable", 503, "The view transform is not available on this server",    false, false},
    {ErrorCode::request_timeout,            "request_timeout",            408, "The request did not arrive in time",                    false, false},
    {ErrorCode::headers_too_large,          "headers_too_large",          431, "The request head is too large",                         false, false},
    {ErrorCode::unsupported_transfer_encoding, "unsupported_transfer_encoding", 501, "The transfer encoding is not supported",     false, false},
    {ErrorCode::too_many_connections,       "too_many_connections",       429, "Too many connections from this address",                false, true},
    {ErrorCode::rate_limited,               "rate_limited",               429, "Too many requests",                                     false, true},
    {ErrorCode::unauthorized,               "unauthorized",               401, "A valid API key is required",                           false, false},
    {ErrorCode::store_unavailable,          "store_unavailable",          503, "The shared store is unavailable",                       false, true},
    {ErrorCode::worker_lost,                "worker_lost",                503, "A render worker was lost",                              false, true},
    {ErrorCode::course_invalid,             "course_invalid",             422, "The course profile is not valid",                       false, false},
    {ErrorCode::unknown_course,             "unknown_course",             404, "No such course",                                        false, false},
    {ErrorCode::grader_failed,              "grader_failed",              500, "The grader's own work failed",                          false, false},
    {ErrorCode::frames_invalid,             "frames_invalid",             422, "A saved frame cannot be read",                          true,  false},
    {ErrorCode::reference_private,          "reference_private",          403, "The course's references are for its staff",             false, false},
    {ErrorCode::driver_refused,             "driver_refused",             500, "This server's graphics driver refuses shaders the browser runs", false, false},
};
}  // namespace

std::span<const ErrorCodeInfo> error_codes() { return kCodes; }

const ErrorCodeInfo& info(ErrorCode code) {
  const auto index = static_cast<size_t>(code);
  SHADELAB_CHECK(index < std::size(kCodes) && kCodes[index].code == code, "error code table out of enum order");
  return kCodes[index];
}

std::optional<ErrorCode> error_code_named(std::string_view name) {
  for (const auto& row : kCodes)
    if (row.name == name) return row.code;
  return std::nullopt;
}

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
