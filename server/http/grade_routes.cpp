// POST /api/grade: a submission against a checkpoint or a custom reference, through the grading
// road (road/submission.h). This file parses the request and formats the report; the road
// decides.
#include "core/base64.h"
#include "http/grade_request.h"
#include "http/route_context.h"
#include "road/code_request.h"
#include "road/frames_request.h"
#include "road/submission.h"

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
  auto parsed = parse_frames_grade(raw);
  if (!parsed) return send_problem(res, parsed.error(), req.path);
  auto built = road::frames_submission(course, std::move(parsed->request));
  if (!built) return send_problem(res, built.error(), req.path);
  built->settings.reference_store = c.config.reference_places();
  built->settings.limits = c.config.limits.render;
  auto graded = road::grade_saved_frames(c.pool, course, *built->checkpoint, std::move(built->submission), built->settings);
  if (!graded) {
    c.count(graded.error());
    return send_problem(res, graded.error(), req.path);
  }
  auto& result = graded->result;
  auto& warnings = result.frames.warnings;
  warnings.insert(warnings.end(), parsed->warnings.begin(), parsed->warnings.end());
  warnings.insert(warnings.end(), built->warnings.begin(), built->warnings.end());
  json body = {{"deliverable", built->checkpoint->name}, {"frames", grade::to_json(result.frames)}, {"seconds", graded->seconds}};
  if (result.code) body["code"] = grade::to_json(*result.code);
  if (!result.heatmap_png.empty()) body["heatmap"] = base64_encode(result.heatmap_png);
  send_json(res, 200, body);
}

// The code's grade: the road's answer for what parsed, or, when a field could not be read, the
// student's source when that is what is wrong (labelled with the checkpoint and points the request
// named, read leniently: a source problem is the student's grade even beside a mistyped field).
// `format` is the result's, as the request asked.
Expected<road::CodeGrade> graded_code(RouteContext& c, const RawRequest& raw, const course::Course& course, const course::Viewer& viewer,
                                      std::string& format) {
  const render::RenderLimits& limits = c.config.limits.render;
  auto parsed = parse_code_grade(raw, c.config.limits);
  if (parsed)
    if (auto s = c.find_uploaded_mesh(parsed->request.mesh, course); !s) parsed = s.take_error();
  format = parsed ? parsed->result_format : field_or<std::string>(raw.fields, "format", "json");
  if (!parsed) {
    auto shaders = read_shaders(raw, c.config.limits);
    return road::grade_misread(parsed.error(), shaders ? shaders->code : std::nullopt, field_or<std::string>(raw.fields, "reference", "custom"),
                               field_or<double>(raw.fields, "maxScore", 1.0), limits);
  }
  auto built = road::code_submission(course, std::move(parsed->request), viewer, limits);
  if (!built) return built.take_error();
  built->submission.spec.reference_store = c.config.reference_places();
  auto graded = road::grade_code(c.pool, std::move(built->submission));
  if (graded) {
    auto& warnings = graded->result.report.warnings;
    warnings.insert(warnings.end(), parsed->warnings.begin(), parsed->warnings.end());
    warnings.insert(warnings.end(), built->warnings.begin(), built->warnings.end());
  }
  return graded;
}

void grade(RouteContext& c, const course::Viewer& viewer, const httplib::Request& req, httplib::Response& res) {
  auto raw = read_request(req);
  if (!raw) return send_problem(res, raw.error(), req.path);
  auto course = course_of(*raw, c.courses);
  if (!course) return send_problem(res, course.error(), req.path);
  if (has_saved_frames(*raw)) return grade_saved(c, *raw, **course, req, res);
  std::string format = "json";
  auto graded = graded_code(c, *raw, **course, viewer, format);
  if (!graded) {
    c.count(graded.error());
    return send_problem(res, graded.error(), req.path);
  }
  if (format == "gradescope") return send_json(res, 200, grade::to_gradescope(graded->result.report, graded->seconds));
  json body = grade::to_json(graded->result.report);
  if (!graded->result.heatmap_png.empty()) body["heatmap"] = base64_encode(graded->result.heatmap_png);
  send_json(res, 200, body);
}

}  // namespace

void add_grade_routes(httplib::Server& server, RouteContext& c) {
  add_route(server, c, Method::post, "/api/grade", grade);
}

}  // namespace shadelab::http
