#pragma once
// A job as it travels to a worker: everything resolved (presets expanded, uploaded meshes attached
// as the message payload), validated by the HTTP layer before it is sent.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "grade/checkpoints.h"
#include "grade/grader.h"
#include "render/render_request.h"

namespace shadelab::worker {

enum class JobKind { render, compile, mesh_check, grade };
enum class Output { grid, frames, json };
enum class Format { png, exr };

// What a grade job compares the submission (the job's shaders) against.
struct GradeSpec {
  std::string reference_name;  // a checkpoint, or "custom"
  shader::ShaderFile reference_vertex, reference_fragment;
  std::vector<grade::Mistake> mistakes;
  std::vector<grade::Probe> probes;
  grade::GradeOptions options;
};

struct Job {
  JobKind kind = JobKind::render;
  render::RenderRequest request;  // shaders, size, frames, msaa, uniforms, pixel type
  std::string mesh = "bunny";     // built-in name, or an uploaded mesh's id (its bytes in the payload)
  std::string mesh_format;        // file extension of an uploaded mesh
  bool fit = false;
  std::string prefix = "render";
  Output output = Output::grid;
  Format format = Format::png;
  GradeSpec grade;  // for JobKind::grade
};

nlohmann::json to_json(const Job& job);
Expected<Job> job_from_json(const nlohmann::json& j);

nlohmann::json to_json(const Error& error);
Error error_from_json(const nlohmann::json& j);
nlohmann::json to_json(const Diagnostic& d);

std::string_view to_string(Output o);
std::string_view to_string(Format f);

}  // namespace shadelab::worker
