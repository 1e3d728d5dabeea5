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

namespace {
json file_json(const shader::ShaderFile& f) { return {{"name", f.name}, {"text", f.text}}; }
shader::ShaderFile file_from(const json& j) { return {j.at("name"), j.at("text")}; }
const char* kind_name(JobKind k) {
  switch (k) {
    case JobKind::render: return "render";
    case JobKind::compile: return "compile";
    case JobKind::mesh_check: return "mesh_check";
    case JobKind::grade: return "grade";
  }
  return "render";
}
}  // namespace

json to_json(const Job& job) {
  const auto& r = job.request;
  json uniforms = json::array();
  for (const auto& u : r.uniforms) uniforms.push_back({{"name", u.name}, {"values", u.values}});
  json mistakes = json::array();
  for (const auto& m : job.grade.mistakes)
    mistakes.push_back({{"id", m.id}, {"message", m.message}, {"vertex", file_json(m.vertex)}, {"fragment", file_json(m.fragment)}});
  json probes = json::array();
  for (const auto& p : job.grade.probes) probes.push_back({{"name", p.name}, {"lightPosition", p.light_position}});
  const auto& o = job.grade.options;
  const json grade = {{"referenceName", job.grade.reference_name},
                      {"referenceVertex", file_json(job.grade.reference_vertex)},
                      {"referenceFragment", file_json(job.grade.reference_fragment)},
                      {"mistakes", mistakes},
                      {"probes", probes},
                      {"threshold", o.compare.threshold},
                      {"spatialTolerance", o.compare.spatial_tolerance},
                      {"maxFailingFraction", o.max_failing_fraction},
                      {"maxScore", o.max_score}};
  return {{"kind", kind_name(job.kind)},
          {"grade", grade},
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
    for (auto k : {JobKind::render, JobKind::compile, JobKind::mesh_check, JobKind::grade})
      if (kind == kind_name(k)) job.kind = k;
    const json& g = j.at("grade");
    job.grade.reference_name = g.at("referenceName");
    job.grade.reference_vertex = file_from(g.at("referenceVertex"));
    job.grade.reference_fragment = file_from(g.at("referenceFragment"));
    for (const auto& m : g.at("mistakes"))
      job.grade.mistakes.push_back({m.at("id"), m.at("message"), file_from(m.at("vertex")), file_from(m.at("fragment"))});
    for (const auto& p : g.at("probes")) job.grade.probes.push_back({p.at("name"), p.at("lightPosition").get<std::array<float, 3>>()});
    job.grade.options.compare.threshold = g.at("threshold");
    job.grade.options.compare.spatial_tolerance = g.at("spatialTolerance");
    job.grade.options.max_failing_fraction = g.at("maxFailingFraction");
    job.grade.options.max_score = g.at("maxScore");
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
