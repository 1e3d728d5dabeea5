// What the service says about itself: presets, the OpenAPI document, health and metrics.
#include "core/embedded_files.h"
#include "http/route_context.h"
#include "render/presets.h"

namespace shadelab::http {

namespace {

using nlohmann::json;

void presets(const httplib::Request&, httplib::Response& res) {
  json out = json::array();
  for (const auto& p : render::presets())
    out.push_back({{"name", p.name},
                   {"description", p.description},
                   {"vertex", {{"name", p.vertex.name}, {"source", p.vertex.text}}},
                   {"fragment", {{"name", p.fragment.name}, {"source", p.fragment.text}}}});
  send_json(res, 200, out);
}

void openapi(const httplib::Request&, httplib::Response& res) {
  res.set_content(std::string(*embedded_file("docs/openapi.json")), "application/json");
}

}  // namespace

void add_service_routes(httplib::Server& server, RouteContext& c) {
  server.Get("/api/presets", presets);
  server.Get("/api/openapi.json", openapi);
  server.Get("/livez", [](const httplib::Request&, httplib::Response& res) { send_json(res, 200, {{"status", "ok"}}); });
  server.Get("/readyz", [&c](const httplib::Request&, httplib::Response& res) {
    const bool ready = c.pool.ready();
    const auto stats = c.pool.stats();
    if (!ready) res.set_header("Retry-After", "1");
    send_json(res, ready ? 200 : 503,
              {{"ready", ready}, {"renderer", c.pool.renderer()}, {"workers", stats.workers}, {"workersReady", stats.workers_ready}});
  });
  server.Get("/metrics", [&c](const httplib::Request&, httplib::Response& res) {
    res.set_content(c.metrics.render(c.pool.stats(), c.pool.ready()) + render_connection_metrics(c.connections.stats()) +
                        c.tenants.render_metrics() + (c.shared ? c.shared->render_metrics() : std::string()),
                    "text/plain; version=0.0.4");
  });
}

}  // namespace shadelab::http
