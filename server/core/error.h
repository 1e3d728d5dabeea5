#pragma once
// The user-facing error channel: everything a caller or the machine can cause is a value of this
// type, never an exception or an abort. Broken invariants (bugs) go to SHADELAB_CHECK instead.
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace shadelab {

// Stable, snake_case codes; each maps to one HTTP status (table in error.cpp and docs/errors.md).
enum class ErrorCode {
  invalid_argument,        // a request field out of range or of the wrong shape
  unknown_preset,
  shader_source_invalid,   // the JS module could not be unwrapped, NUL bytes, too long, ...
  missing_version,         // no `#version 300 es` on the first line (WebGL2 requires it)
  compile_failed,
  link_failed,
  uniform_type_mismatch,
  mesh_not_found,
  mesh_parse_failed,
  mesh_invalid,            // NaN/Inf coordinates and the like
  mesh_empty,
  mesh_too_large,          // over the triangle cap
  msaa_unsupported,
  egl_unavailable,
  gl_error,
  io_error,
  // What the HTTP process reports about a worker (server/worker/pool.cpp).
  queue_full,              // 503 with Retry-After
  compile_timeout,
  render_timeout,
  compile_crashed,
  render_crashed,
  out_of_memory,
  not_ready,               // no worker could be started
  payload_too_large,
  not_found,
  worker_protocol,         // a worker sent something we cannot read (a bug)
  view_transform_unavailable,  // Filmic asked for, but no OCIO config on this server
  // What the connection layer and the tenant checks answer (server/http/connection_server.cpp,
  // server/http/tenants.cpp) before a request reaches a route.
  request_timeout,         // the request head or body did not arrive within its deadline
  headers_too_large,       // the request head is over its byte limit
  unsupported_transfer_encoding,  // a Transfer-Encoding other than chunked
  too_many_connections,    // this address holds its share of connections already
  rate_limited,            // this key or address is over its request rate
  unauthorized,            // API keys are required and none, or a wrong one, was sent
  // What a replica answers when the shared store (server/store/) holds the only copy it could use.
  store_unavailable,       // an uploaded mesh is on another replica and Redis cannot be reached
  // What the pool answers when a worker stops answering for a reason that is not the shader's.
  worker_lost,             // the worker was stopped (SIGSTOP) or dropped its socket without exiting
  // What loading a course profile (server/course/) and naming a course in a request can answer.
  course_invalid,          // the profile's field named in the message is missing or wrong
  unknown_course,          // a request names a course this server does not hold
  // What grading answers when its own work (the reference, the known mistakes) fails: never the
  // submission's doing, so never its grade.
  grader_failed,           // the grader's renders ran over their CPU budget, crashed or ran out of memory
  frames_invalid,          // a saved frame cannot be read: not a PNG, truncated, larger than a canvas
  reference_private,       // a reference's source or frames asked for without a staff key
  driver_refused,          // the driver refuses shaders ShadeLab's front end (the browser's rules) accepts
};

// Everything known about a code, in one row of the table in error.cpp.
struct ErrorCodeInfo {
  ErrorCode code;
  std::string_view name;       // stable, snake_case: the `code` of problem+json and of the worker wire
  int status;                  // HTTP status
  std::string_view title;      // problem+json `title`: the same for every error of this code
  bool submission_caused;      // the submitted shaders caused it: a grade of 0, not a service error
  bool retry_later;            // the service is busy or starting: answered with Retry-After
};

// Every code, in enum order (a test checks that each enumerator has exactly one row).
std::span<const ErrorCodeInfo> error_codes();
const ErrorCodeInfo& info(ErrorCode code);
// The code of that name; nullopt for a name no row holds.
std::optional<ErrorCode> error_code_named(std::string_view name);

inline std::string_view to_string(ErrorCode code) { return info(code).name; }
inline int http_status(ErrorCode code) { return info(code).status; }

// One compiler-style message, located in the student's own file.
struct Diagnostic {
  std::string stage;     // "vertex", "fragment" or "link"
  std::string file;      // the name the student knows (phong_frag.js)
  int line = 0;          // 1-based in `file`; 0 when the driver gave no location
  int column = 0;        // 1-based; 0 when unknown
  std::string severity;  // "error" or "warning"
  std::string message;

  // "phong_frag.js:12:5: error: message", as compilers print it.
  std::string format() const;
};

struct Error {
  ErrorCode code;
  std::string message;                   // a sentence a student understands
  std::vector<Diagnostic> diagnostics;   // empty when not about shader source
  std::string driver_log;                // the driver's info log, verbatim

  std::string format() const;            // message plus one line per diagnostic
};

}  // namespace shadelab
