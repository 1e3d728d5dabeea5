// POST /api/grade: a submission against a checkpoint or a custom reference, through a worker.
#include "core/base64.h"
#include "http/frames_request.h"
#include "http/route_context.h"

namespace shadelab::http {

namespace {

using nlohmann::json;

template <class T>
T field_or(const json& fields, const char* name, T fallback) {
  if (!fields.contains(name)) return fallback;
  const json& v = fields[name];
  if constexpr (std::is_same_v<T, std::string>) return v.is_string() ? v.get<std::string>() : fallback;
  else return v.is_number() ? v.get<T>() : fallback;
}

// Saved frames, and the code beside them: {"frames": report, "code": report, "heatmap"}; a frame
// missing, not a PNG or the wrong size is the frames' grade (0, the file named), as on Gradescope.
void grade_saved(RouteContext& c, const RawRequest& raw, const course::Course& course, const httplib::Request& req,
                 httplib::Response& res) {
  auto parsed = parse_frames_grade(raw, course);
  if (!parsed) return send_problem(res, parsed.error(), req.path);
  parsed->settings.reference_store = c.config.reference_places();
  auto graded = worker::grade_frame_set(c.pool, course, *parsed->checkpoint, std::move(parsed->submission), parsed->settings);
  if (!graded) return send_problem(res, graded.error(), req.path);
  auto& result = graded->result;
  result.frames.warnings.insert(result.frames.warnings.end(), parsed->warnings.begin(), parsed->warnings.end());
  json body = {{"deliverable", parsed->checkpoint->name}, {"frames", grade::to_json(result.frames)}, {"seconds", graded->seconds}};
  if (result.code) body["code"] = grade::to_json(*result.code);
  if (!result.heatmap_png.empty()) body["heatmap"] = base64_encode(result.heatmap_png);
  send_json(res, 200, body);
}

void grade(RouteContext& c, const httplib::Request& req, httplib::Response& res) {
  auto raw = read_request(req);
  if (!raw) return send_problem(res, raw.error(), req.path);
  if (has_saved_frames(*raw)) {
    auto course = course_of(*raw, c.courses);
    if (!course) return send_problem(res, course.error(), req.path);
    return grade_saved(c, *raw, **course, req, res);
  }
  // Read without throwing: parse_grade_job type-checks these, but its error path below still
  // needs them, whatever the client sent.
  const std::string checkpoint = field_or<std::string>(raw->fields, "reference", "custom");
  const std::string format = field_or<std::string>(raw->fields, "format", "json");
  const double max_score = field_or<double>(raw->fields, "maxScore", 1.0);
  auto course = course_of(*raw, c.courses);
  if (!course) return send_problem(res, course.error(), req.path);
  auto parsed = parse_grade_job(*raw, c.config.limits, **course);
  worker::GradeResult graded;
  double seconds = 0;
  if (!parsed) {
    // The submission's own source problems are its grade; a malformed request is not.
    if (!info(parsed.error().code).submission_caused) return send_problem(res, parsed.error(), req.path);
    graded.report = grade::failed_submission(parsed.error(), checkpoint, max_score);
  } else {
    if (auto visible = c.may_draw(parsed->parsed, **course, req); !visible) return send_problem(res, visible.error(), req.path);
    auto mesh = c.mesh_bytes(parsed->parsed);
    if (!mesh) return send_problem(res, mesh.error(), req.path);
    parsed->parsed.job.grade.reference_store = c.config.reference_places();
    auto answered = worker::grade(c.pool, parsed->parsed.job, std::move(*mesh));
    if (!answered) return send_problem(res, answered.error(), req.path);
    graded = std::move(answered->result);
    seconds = (answered->queue_ms + answered->worker_ms) / 1000;
    graded.report.warnings.insert(graded.report.warnings.end(), parsed->parsed.warnings.begin(), parsed->parsed.warnings.end());
  }
  if (format == "gradescope") return send_json(res, 200, grade::to_gradescope(graded.report, seconds));
  json body = grade::to_json(graded.report);
  if (!graded.heatmap_png.empty()) body["heatmap"] = base64_encode(graded.heatmap_png);
  send_json(res, 200, body);
}

}  // namespace

void add_grade_routes(httplib::Server& server, RouteContext& c) {
  server.Post("/api/grade", [&c](const httplib::Request& req, httplib::Response& res) { grade(c, req, res); });
}

}  // namespace shadelab::http
