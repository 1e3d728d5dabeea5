// POST /api/scene (a scene in Blender's terms through a worker), GET /api/scenes[/name] (the
// example scenes) and GET /api/dolly (dolly-zoom distances). With a PNG body, the report travels
// in headers: X-ShadeLab-Passes / -Features / -Framing and Server-Timing.
#include "http/scene_routes.h"

#include <cstdio>
#include <set>

#include "core/base64.h"
#include "core/embedded_files.h"
#include "core/number_list.h"
#include "http/route_context.h"
#include "scene/dolly_zoom.h"
#include "scene/mesh.h"
#include "scene/scene_mesh.h"

namespace shadelab::http {

using nlohmann::json;

namespace {
// Object names are the user's: keep header values to a token-safe alphabet.
std::string token(std::string_view s) {
  std::string out;
  for (char c : s) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-') ? c : '_';
  return out.empty() ? "_" : out;
}
std::string fixed(double v, int digits) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}
}  // namespace

std::string scene_passes_header(const scene_render::SceneReport& report) {
  std::string out;
  for (const auto& p : report.passes) out += (out.empty() ? "" : ", ") + token(p.name()) + ";dur=" + fixed(p.ms, 2);
  return out;
}

std::string scene_framing_header(const scene_render::SceneReport& report) {
  std::string out;
  for (const auto& f : report.framing) {
    const std::string state = !f.drawn ? "not-drawn" : f.behind_camera ? "behind-camera" : f.fully_visible ? "fully-visible" : "cropped";
    out += (out.empty() ? "" : ", ") + token(f.name) + ";" + state + ";in-frame=" + fixed(f.fraction_in_frame, 3) +
           ";coverage=" + fixed(f.image_coverage, 4);
  }
  return out;
}

std::string scene_features_header(const scene_render::SceneReport& report) {
  std::string out;
  for (const auto& f : report.features) out += (out.empty() ? "" : ", ") + f;
  return out.empty() ? "none" : out;
}

namespace {

// Every mesh the objects name that is not built in: a file part of that name, or an uploaded id.
Expected<std::vector<worker::SceneMeshBytes>> scene_meshes(RouteContext& c, const scene::SceneDescription& scene,
                                                           const std::map<std::string, UploadedFile>& files) {
  std::vector<worker::SceneMeshBytes> out;
  std::set<std::string> attached;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const std::string& ref = scene.objects[i].mesh;
    if (!attached.insert(ref).second) continue;
    if (auto f = files.find(ref); f != files.end()) {
      out.push_back({ref, scene::mesh_format_of(f->second.filename), f->second.content});
    } else if (!scene::is_builtin_scene_mesh(ref)) {
      const auto stored = c.meshes.get(ref);
      if (!stored) return stored.error();
      if (!*stored) {
        std::string builtins;
        for (const auto& n : scene::builtin_scene_mesh_names()) builtins += (builtins.empty() ? "" : ", ") + n;
        return make_error(ErrorCode::mesh_not_found, "objects[" + std::to_string(i) + "].mesh: no mesh '" + ref + "' (built-ins: " +
                                                         builtins + "; or an id from POST /api/meshes, or a multipart file part of that name)");
      }
      out.push_back({ref, (*stored)->format, (*stored)->bytes});
    }
  }
  return out;
}

bool wants_json(const httplib::Request& req) {
  const std::string accept = req.get_header_value("Accept");
  return req.get_param_value("format") == "json" ||
         (accept.find("application/json") != std::string::npos && accept.find("image/png") == std::string::npos);
}

void render_scene(RouteContext& c, const course::Viewer&, const httplib::Request& req, httplib::Response& res) {
  auto upload = read_scene(req);
  if (!upload) return send_problem(res, upload.error(), req.path);
  auto description = scene::parse_scene(upload->scene, c.config.limits.scene);
  if (!description) return send_problem(res, description.error(), req.path);
  auto meshes = scene_meshes(c, *description, upload->files);
  if (!meshes) return send_problem(res, meshes.error(), req.path);
  worker::Message message = worker::to_message(worker::SceneJob{std::move(*description), std::move(*meshes)});
  const bool as_json = wants_json(req);
  const std::string etag = c.etag_of(message, as_json ? "json" : "png");
  if (c.answered_from_cache(req, res, etag)) return;
  auto answered = c.run<worker::SceneResult>(std::move(message));
  if (!answered) return send_problem(res, answered.error(), req.path);
  auto& r = answered->result;
  c.metrics.phase("render", r.report.total_ms / 1000);
  c.metrics.phase("encode", r.encode_ms / 1000);

  CachedResponse response;
  response.headers["X-ShadeLab-Passes"] = scene_passes_header(r.report);
  response.headers["X-ShadeLab-Features"] = scene_features_header(r.report);
  response.headers["Server-Timing"] = "queue;dur=" + std::to_string(answered->queue_ms) + ", " + scene_passes_header(r.report);
  if (!r.report.framing.empty()) response.headers["X-ShadeLab-Framing"] = scene_framing_header(r.report);
  if (as_json) {
    json report = r.report;
    report["renderer"] = c.pool.renderer();
    report["queueMs"] = answered->queue_ms;
    report["encodeMs"] = r.encode_ms;
    report["image"] = base64_encode(r.png);
    response.content_type = "application/json";
    response.body = json_text(report);
  } else {
    response.content_type = "image/png";
    response.body = std::move(r.png);
  }
  c.send_and_cache(res, etag, std::move(response));
}

// GET /api/dolly?subject=0,0,0&from=0,-4,0&lens=25&lenses=25,50,100
void dolly(RouteContext&, const course::Viewer&, const httplib::Request& req, httplib::Response& res) {
  const auto numbers = [&](const char* name, std::vector<double> fallback, size_t count) -> Expected<std::vector<double>> {
    if (!req.has_param(name)) return fallback;
    return parse_number_list(req.get_param_value(name), name, {.count = count});
  };
  auto subject = numbers("subject", {0, 0, 0}, 3);
  auto from = numbers("from", {0, -4, 0}, 3);
  auto lens = numbers("lens", {25}, 1);
  auto lenses = numbers("lenses", {25, 50, 100}, 0);
  for (auto* e : {&subject, &from, &lens, &lenses})
    if (!*e) return send_problem(res, e->error(), req.path);
  if ((*lens)[0] <= 0 || lenses->empty() || lenses->size() > 64 || std::any_of(lenses->begin(), lenses->end(), [](double l) { return l <= 0; }))
    return send_problem(res, make_error(ErrorCode::invalid_argument, "lens and lenses: positive focal lengths in mm (at most 64)"), req.path);
  json stops = json::array();
  const auto& s = *subject;
  const auto& f = *from;
  for (const auto& stop : scene::dolly_zoom({s[0], s[1], s[2]}, {f[0], f[1], f[2]}, (*lens)[0], *lenses))
    stops.push_back({{"lens", stop.lens_mm}, {"distance", stop.distance}, {"location", {stop.location.x, stop.location.y, stop.location.z}}});
  send_json(res, 200, {{"stops", stops}});
}

// The example scenes (assets/scenes/), ready to POST back to /api/scene.
void list_scenes(RouteContext&, const course::Viewer&, const httplib::Request&, httplib::Response& res) {
  json out = json::array();
  constexpr std::string_view prefix = "assets/scenes/", suffix = ".json";
  for (const auto& f : embedded_files())
    if (f.path.starts_with(prefix)) out.push_back(std::string(f.path.substr(prefix.size(), f.path.size() - prefix.size() - suffix.size())));
  send_json(res, 200, {{"scenes", out}});
}

void example_scene(RouteContext&, const course::Viewer&, const httplib::Request& req, httplib::Response& res) {
  const std::string name = req.matches[1];
  const auto text = embedded_file("assets/scenes/" + name + ".json");
  if (!text) return send_problem(res, make_error(ErrorCode::not_found, "no example scene '" + name + "'"), req.path);
  res.set_content(std::string(*text), "application/json");
}

}  // namespace

void add_scene_routes(httplib::Server& server, RouteContext& c) {
  add_route(server, c, Method::post, "/api/scene", render_scene);
  add_route(server, c, Method::get, "/api/dolly", dolly);
  add_route(server, c, Method::get, "/api/scenes", list_scenes);
  add_route(server, c, Method::get, R"(/api/scenes/([a-z0-9_]+))", example_scene);
}

}  // namespace shadelab::http
