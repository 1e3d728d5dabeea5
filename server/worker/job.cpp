#include "worker/job.h"

namespace shadelab::worker {

using nlohmann::json;

std::string_view to_string(Output o) { return o == Output::grid ? "grid" : o == Output::frames ? "frames" : "json"; }
std::string_view to_string(Format f) { return f == Format::png ? "png" : "exr"; }

json to_json(const Diagnostic& d) {
  return {{"stage", d.stage}, {"file", d.file}, {"line", d.line}, {"column", d.column}, {"severity", d.severity},
          {"message", d.message}};
}

json to_json(const Error& e) {
  json diagnostics = json::array();
  for (const auto& d : e.diagnostics) diagnostics.push_back(to_json(d));
  return {{"code", to_string(e.code)}, {"message", e.message}, {"diagnostics", diagnostics}, {"driverLog", e.driver_log}};
}

Error error_from_json(const json& j) {
  Error e{ErrorCode::io_error, j.value("message", "unknown error"), {}, j.value("driverLog", "")};
  const std::string code = j.value("code", "");
  for (int i = 0; i <= static_cast<int>(ErrorCode::worker_protocol); ++i)
    if (to_string(static_cast<ErrorCode>(i)) == code) e.code = static_cast<ErrorCode>(i);
  for (const auto& d : j.value("diagnostics", json::array()))
    e.diagnostics.push_back({d.value("stage", ""), d.value("file", ""), d.value("line", 0), d.value("column", 0),
                             d.value("severity", "error"), d.value("message", "")});
  return e;
}

json to_json(const Job& job) {
  const auto& r = job.request;
  json uniforms = json::array();
  for (const auto& u : r.uniforms) uniforms.push_back({{"name", u.name}, {"values", u.values}});
  return {{"kind", job.kind == JobKind::render ? "render" : job.kind == JobKind::compile ? "compile" : "mesh_check"},
          {"vertex", r.vertex.text},
          {"vertexName", r.vertex.name},
          {"fragment", r.fragment.text},
          {"fragmentName", r.fragment.name},
          {"width", r.width},
          {"height", r.height},
          {"frames", r.frames},
          {"degreesPerFrame", r.degrees_per_frame},
          {"msaa", r.msaa},
          {"uniforms", uniforms},
          {"mesh", job.mesh},
          {"meshFormat", job.mesh_format},
          {"fit", job.fit},
          {"prefix", job.prefix},
          {"output", to_string(job.output)},
          {"format", to_string(job.format)}};
}

Expected<Job> job_from_json(const json& j) {
  try {
    Job job;
    const std::string kind = j.at("kind");
    job.kind = kind == "render" ? JobKind::render : kind == "compile" ? JobKind::compile : JobKind::mesh_check;
    auto& r = job.request;
    r.vertex = {j.at("vertexName"), j.at("vertex")};
    r.fragment = {j.at("fragmentName"), j.at("fragment")};
    r.width = j.at("width");
    r.height = j.at("height");
    r.frames = j.at("frames");
    r.degrees_per_frame = j.at("degreesPerFrame");
    r.msaa = j.at("msaa");
    for (const auto& u : j.at("uniforms")) r.uniforms.push_back({u.at("name"), u.at("values").get<std::vector<double>>()});
    job.mesh = j.at("mesh");
    job.mesh_format = j.at("meshFormat");
    job.fit = j.at("fit");
    job.prefix = j.at("prefix");
    const std::string output = j.at("output");
    job.output = output == "grid" ? Output::grid : output == "frames" ? Output::frames : Output::json;
    job.format = j.at("format") == "exr" ? Format::exr : Format::png;
    r.pixel_type = job.format == Format::exr ? image::PixelType::f32 : image::PixelType::u8;
    return job;
  } catch (const json::exception& e) {
    return make_error(ErrorCode::worker_protocol, std::string("malformed job: ") + e.what());
  }
}

}  // namespace shadelab::worker
