// POST /api/grade: a submission against a checkpoint or a custom reference, through the grading
// road (road/client_grade.h). This file parses the request and formats the report; the road
// decides.
#include "core/base64.h"
#include "http/grade_request.h"
#include "http/route_context.h"
#include "road/client_grade.h"

namespace shadelab::http {

namespace {

using nlohmann::json;

// The report as JSON: saved frames' {"deliverable", "frames", "code", "seconds", "heatmap"}; code's
// report, or Gradescope's results.json when the request asked for it.
json body_of(const road::ClientGraded& graded, const std::string& format) {
  if (const auto* frames = std::get_if<road::FramesGrade>(&graded.grade)) {
    const auto& result = frames->result;
    json body = {{"deliverable", graded.deliverable}, {"frames", grade::to_json(result.frames)}, {"seconds", frames->seconds}};
    if (result.code) body["code"] = grade::to_json(*result.code);
    if (!result.heatmap_png.empty()) body["heatmap"] = base64_encode(result.heatmap_png);
    return body;
  }
  const auto& code = std::get<road::CodeGrade>(graded.grade);
  if (format == "gradescope") return grade::to_gradescope(code.result.report, code.seconds);
  json body = grade::to_json(code.result.report);
  if (!code.result.heatmap_png.empty()) body["heatmap"] = base64_encode(code.result.heatmap_png);
  return body;
}

// Saved frames (and the code beside them) or code, read, then one call down the road. A frame
// missing, not a PNG or the wrong size is the frames' grade (0, the file named), as on Gradescope;
// a mesh named by an uploaded id is looked up here, where the uploads are kept.
void grade(RouteContext& c, const course::Viewer& viewer, const httplib::Request& req, httplib::Response& res) {
  auto raw = read_request(req);
  if (!raw) return send_problem(res, raw.error(), req.path);
  auto course = course_of(*raw, c.courses);
  if (!course) return send_problem(res, course.error(), req.path);
  auto parsed = parse_grade(*raw, c.config.limits);
  if (!parsed) return send_problem(res, parsed.error(), req.path);
  road::ClientGrade& asked = parsed->grade;
  if (auto* code = std::get_if<road::CodeRequest>(&asked.request); code && !asked.unread)
    if (auto s = c.find_uploaded_mesh(code->mesh, **course); !s) asked.unread = s.take_error();
  const road::ClientRoad lent{c.pool, c.config.limits.render, c.config.reference_places(), c.config.repair};
  auto graded = road::grade_for_client(lent, **course, std::move(asked), viewer);
  if (!graded) {
    c.count(graded.error());
    return send_problem(res, graded.error(), req.path);
  }
  send_json(res, 200, body_of(*graded, parsed->result_format));
}

}  // namespace

void add_grade_routes(httplib::Server& server, RouteContext& c) {
  add_route(server, c, Method::post, "/api/grade", grade);
}

}  // namespace shadelab::http
