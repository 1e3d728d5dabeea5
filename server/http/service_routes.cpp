// What the service says about itself: its courses and their presets, the OpenAPI document,
// health and metrics.
#include "core/embedded_files.h"
#include "course/access.h"
#include "course/course_reader.h"
#include "http/course_facts.h"
#include "http/route_context.h"

namespace shadelab::http {

namespace {

using nlohmann::json;

void openapi(RouteContext&, const course::Viewer&, const httplib::Request&, httplib::Response& res) {
  res.set_content(std::string(*embedded_file("docs/openapi.json")), "application/json");
}

void presets(RouteContext& c, const course::Viewer& viewer, const httplib::Request& req, httplib::Response& res) {
  if (const auto* course = c.course_param(req, res)) send_json(res, 200, presets_json(*course, viewer));
}

void course_facts(RouteContext& c, const course::Viewer& viewer, const httplib::Request& req, httplib::Response& res) {
  if (const auto* course = c.course_param(req, res)) send_json(res, 200, course_json(*course, viewer));
}

void courses(RouteContext& c, const course::Viewer&, const httplib::Request&, httplib::Response& res) {
  json out = json::array();
  for (const auto& course : c.courses.all()) out.push_back({{"id", course->id}, {"title", course->title}});
  send_json(res, 200, {{"default", c.courses.default_course().id}, {"courses", out}});
}

void livez(RouteContext&, const course::Viewer&, const httplib::Request&, httplib::Response& res) { send_json(res, 200, {{"status", "ok"}}); }

void readyz(RouteContext& c, const course::Viewer&, const httplib::Request&, httplib::Response& res) {
  const bool ready = c.pool.ready();
  const auto stats = c.pool.stats();
  if (!ready) res.set_header("Retry-After", "1");
  send_json(res, ready ? 200 : 503,
            {{"ready", ready}, {"renderer", c.pool.renderer()}, {"workers", stats.workers}, {"workersReady", stats.workers_ready}});
}

void metrics(RouteContext& c, const course::Viewer&, const httplib::Request&, httplib::Response& res) {
  res.set_content(c.metrics.render(c.pool.stats(), c.pool.ready()) + render_connection_metrics(c.connections.stats()) +
                      c.tenants.render_metrics() + (c.shared ? c.shared->render_metrics() : std::string()),
                  "text/plain; version=0.0.4");
}

}  // namespace

void add_service_routes(httplib::Server& server, RouteContext& c) {
  add_route(server, c, Method::get, "/api/presets", presets);
  add_route(server, c, Method::get, "/api/course", course_facts);
  add_route(server, c, Method::get, "/api/courses", courses);
  add_route(server, c, Method::get, "/api/openapi.json", openapi);
  add_route(server, c, Method::get, "/livez", livez);
  add_route(server, c, Method::get, "/readyz", readyz);
  add_route(server, c, Method::get, "/metrics", metrics);
}

}  // namespace shadelab::http
