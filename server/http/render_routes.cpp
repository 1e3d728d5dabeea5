// POST/GET /api/render and POST /api/compile: the homework's spinning mesh, through a worker.
#include "core/base64.h"
#include "http/route_context.h"

namespace shadelab::http {

namespace {

using nlohmann::json;

std::string server_timing(const worker::RenderTimings& t, double queue_ms) {
  std::string out = "queue;dur=" + std::to_string(queue_ms);
  for (const auto& [phase, ms] : {std::pair{"compile", t.compile_ms}, {"render", t.render_ms}, {"readback", t.readback_ms}, {"encode", t.encode_ms}})
    out += std::string(", ") + phase + ";dur=" + std::to_string(ms);
  return out;
}

void record_phases(Metrics& metrics, const worker::RenderTimings& t) {
  for (const auto& [phase, ms] : {std::pair{"compile", t.compile_ms}, {"upload", t.upload_ms}, {"firstFrame", t.first_frame_ms},
                                  {"render", t.render_ms}, {"readback", t.readback_ms}, {"encode", t.encode_ms}})
    metrics.phase(phase, ms / 1000);
}

// The request's warnings, then the worker's, then one per frame that came out one colour.
std::vector<std::string> warnings_of(const ParsedJob& parsed, const worker::RenderResult& r) {
  std::vector<std::string> warnings = parsed.warnings;
  warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
  for (const auto& c : r.constant_frames)
    warnings.push_back("frame " + std::to_string(c.frame) + " is one constant colour " + json(c.rgba).dump() +
                       ": nothing was drawn, or the shader writes the same colour everywhere");
  return warnings;
}

// output=json: the images base64-encoded beside the report.
std::string json_body(const worker::RenderResult& r, const std::vector<std::string>& warnings, const std::string& renderer, double queue_ms) {
  json frames = json::array();
  for (const auto& f : r.frames) frames.push_back({{"name", f.name}, {"data", base64_encode(f.bytes)}});
  json timings = r.timings;
  timings["queue"] = queue_ms;
  return json_text({{"renderer", renderer},
                    {"samples", r.samples},
                    {"warnings", warnings},
                    {"diagnostics", r.diagnostics},
                    {"constantFrames", r.constant_frames},
                    {"attributes", r.attributes},
                    {"uniforms", r.uniforms},
                    {"timings", timings},
                    {"images", {{"grid", base64_encode(r.body)}, {"frames", frames}}}},
                   -1);
}

// The request's job of `kind`, in its course, when `viewer` may see what it draws.
struct VisibleJob {
  const course::Course* course;
  ParsedJob parsed;
};
Expected<VisibleJob> visible_job(RouteContext& c, const course::Viewer& viewer, const httplib::Request& req, worker::JobKind kind) {
  auto raw = read_request(req);
  if (!raw) return raw.take_error();
  auto course = course_of(*raw, c.courses);
  if (!course) return course.take_error();
  auto parsed = parse_job(*raw, kind, c.config.limits, **course);
  if (!parsed) return parsed.take_error();
  if (auto visible = c.may_draw(*parsed, **course, viewer); !visible) return visible.take_error();
  return VisibleJob{*course, std::move(*parsed)};
}

void render(RouteContext& c, const course::Viewer& viewer, const httplib::Request& req, httplib::Response& res) {
  auto visible = visible_job(c, viewer, req, worker::JobKind::render);
  if (!visible) return send_problem(res, visible.error(), req.path);
  const course::Course* course = visible->course;
  auto parsed = &visible->parsed;
  if (parsed->job.output == worker::Output::frames) parsed->job.notice = course->frames_download_notice();
  auto mesh = c.mesh_bytes(*parsed);
  if (!mesh) return send_problem(res, mesh.error(), req.path);
  worker::Message message = worker::to_message(parsed->job, std::move(*mesh));
  const std::string etag = c.etag_of(message, "");
  if (c.answered_from_cache(req, res, etag)) return;

  auto answered = c.run<worker::RenderResult>(std::move(message));
  if (!answered) return send_problem(res, answered.error(), req.path);
  auto& r = answered->result;
  record_phases(c.metrics, r.timings);
  const auto warnings = warnings_of(*parsed, r);
  std::string constant;
  for (const auto& f : r.constant_frames) constant += (constant.empty() ? "" : ",") + std::to_string(f.frame);

  CachedResponse response;
  response.headers["Server-Timing"] = server_timing(r.timings, answered->queue_ms);
  response.headers["X-ShadeLab-Warnings"] = std::to_string(warnings.size());
  if (!constant.empty()) response.headers["X-ShadeLab-Constant-Frames"] = constant;
  if (const std::string notice = course->frames_download_notice(); !notice.empty() && parsed->job.output != worker::Output::grid)
    response.headers["X-ShadeLab-Notice"] = notice;
  if (parsed->job.output == worker::Output::frames)
    response.headers["Content-Disposition"] =
        "attachment; filename=\"" + render::frame_file_name(parsed->job.frame_name, parsed->job.prefix, "frames", "zip") + "\"";
  if (parsed->job.output == worker::Output::json) {
    response.content_type = "application/json";
    response.body = json_body(r, warnings, c.pool.renderer(), answered->queue_ms);
  } else {
    response.content_type = r.content_type;
    response.body = std::move(r.body);
  }
  c.send_and_cache(res, etag, std::move(response));
}

void compile(RouteContext& c, const course::Viewer& viewer, const httplib::Request& req, httplib::Response& res) {
  auto visible = visible_job(c, viewer, req, worker::JobKind::compile);
  if (!visible) return send_problem(res, visible.error(), req.path);
  const ParsedJob* parsed = &visible->parsed;
  auto answered = c.run<worker::CompileResult>(worker::to_message(parsed->job));
  if (!answered) return send_problem(res, answered.error(), req.path);
  const auto& r = answered->result;
  c.metrics.phase("compile", r.compile_ms / 1000);
  std::vector<std::string> warnings = parsed->warnings;
  warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
  res.set_header("X-ShadeLab-Renderer", c.pool.renderer());
  send_json(res, 200, {{"ok", true}, {"renderer", c.pool.renderer()}, {"warnings", warnings},
                       {"diagnostics", r.diagnostics}, {"attributes", r.attributes}, {"uniforms", r.uniforms},
                       {"timings", {{"compile", r.compile_ms}}}});
}

}  // namespace

void add_render_routes(httplib::Server& server, RouteContext& c) {
  add_route(server, c, Method::post, "/api/render", render);
  add_route(server, c, Method::get, "/api/render", render);
  add_route(server, c, Method::post, "/api/compile", compile);
}

}  // namespace shadelab::http
