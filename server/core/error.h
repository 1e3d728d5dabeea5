#pragma once
// The user-facing error channel: everything a caller or the machine can cause is a value of this
// type, never an exception or an abort. Broken invariants (bugs) go to SHADELAB_CHECK instead.
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
};

std::string_view to_string(ErrorCode code);
int http_status(ErrorCode code);

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
