#include "http/service.h"

#include <httplib.h>

#include <chrono>
#include <cstdio>
#include <thread>
#include <set>
#include <cmath>
#include <algorithm>

#include <OpenImageIO/strutil.h>

#include "core/embedded_files.h"
#include "grade/report.h"
#include "http/api_request.h"
#include "worker/grade_client.h"
#include "http/mesh_store.h"
#include "http/metrics.h"
#include "http/problem.h"
#include "http/response_cache.h"
#include "render/presets.h"
#include "scene/dolly_zoom.h"
#include "scene/mesh.h"
#include "scene/scene_description.h"
#include "scene/scene_mesh.h"
#include "http/scene_routes.h"
#include "worker/scene_job.h"

namespace shadelab::http {

namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

thread_local Clock::time_point request_start;

void send_problem(httplib::Response& res, const Error& e, const std::string& instance) {
  res.status = http_status(e.code);
  if (e.code == ErrorCode::queue_full || e.code == ErrorCode::not_ready) res.set_header("Retry-After", "1");
  res.set_content(problem(e, instance).dump(2, ' ', false, json::error_handler_t::replace), "application/problem+json");
}

void send_json(httplib::Response& res, int status, const json& body) {
  res.status = status;
  res.set_content(body.dump(2, ' ', false, json::error_handler_t::replace), "application/json");
}

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

std::string server_timing(const json& t, double queue_ms) {
  std::string out = "queue;dur=" + std::to_string(queue_ms);
  for (const char* phase : {"compile", "render", "readback", "encode"})
    if (t.contains(phase)) out += std::string(", ") + phase + ";dur=" + std::to_string(t[phase].get<double>());
  return out;
}

bool is_builtin_mesh(const std::string& name) {
  for (const auto& n : scene::builtin_mesh_names())
    if (n == name) return true;
  return false;
}

}  // namespace

struct Service::Impl {
  ServiceConfig config;
  httplib::Server server;
  std::unique_ptr<worker::WorkerPool> pool;
  MeshStore meshes;
  ResponseCache cache;
  Metrics metrics;
  std::thread thread;
  int port = 0;

  explicit Impl(ServiceConfig c)
      : config(std::move(c)), meshes(config.limits.max_stored_meshes), cache(config.cache_bytes) {}

  // The request in neutral form, from whichever encoding the client used.
  Expected<RawRequest> read(const httplib::Request& req) {
    if (req.is_multipart_form_data()) {
      std::multimap<std::string, std::string> fields;
      std::map<std::string, UploadedFile> files;
      for (const auto& [name, part] : req.files) {
        if (part.filename.empty()) fields.emplace(name, part.content);
        else files[name] = {part.filename, part.content};
      }
      return from_form(fields, std::move(files));
    }
    if (req.method == "GET") return from_form(req.params, {});
    const std::string type = req.get_header_value("Content-Type");
    if (type.rfind("application/x-www-form-urlencoded", 0) == 0) return from_form(req.params, {});
    if (!type.empty() && type.find("json") == std::string::npos)
      return make_error(ErrorCode::invalid_argument, "send JSON (Content-Type: application/json) or multipart/form-data; got " + type);
    return from_json_body(req.body);
  }

  // Resolves the job's mesh into the message payload: a file in this request, an uploaded id, or
  // a built-in (no payload).
  Status attach_mesh(ParsedJob& parsed, worker::Message& message) {
    if (!parsed.mesh_upload.content.empty()) {
      message.payload = parsed.mesh_upload.content;
    } else if (!is_builtin_mesh(parsed.job.mesh)) {
      const auto stored = meshes.get(parsed.job.mesh);
      if (!stored)
        return make_error(ErrorCode::mesh_not_found, "no mesh '" + parsed.job.mesh +
                                                         "': use bunny, teapot, or the id POST /api/meshes returned");
      message.payload = stored->bytes;
      parsed.job.mesh_format = stored->format;
    }
    message.header = worker::to_json(parsed.job);
    return Ok{};
  }

  Expected<worker::JobResult> run(worker::Message message) {
    auto future = pool->submit(std::move(message));
    if (!future) return future.take_error();
    worker::JobResult result = future->get();
    if (!result.ok) {
      if (result.error.code == ErrorCode::compile_failed || result.error.code == ErrorCode::link_failed) metrics.compile_failure();
      return std::move(result.error);
    }
    metrics.phase("queue", result.queue_ms / 1000);
    const json timings = result.header.value("timings", json::object());  // items() must not outlive it
    for (const auto& [phase, ms] : timings.items())
      if (ms.is_number()) metrics.phase(phase, ms.get<double>() / 1000);
    return result;
  }

  // Same job, same mesh bytes, same renderer, same response form: same bytes out. That makes a
  // strong ETag.
  std::string etag_of(const worker::Message& message, const std::string& form) const {
    const std::string key = form + '\0' + message.header.dump(-1, ' ', false, json::error_handler_t::replace) + '\0' +
                            message.payload + '\0' + pool->renderer();
    return "\"" + hex(fnv1a64(key)) + hex(fnv1a64(key, 0x9e3779b97f4a7c15ull)) + "\"";
  }

  // A 304 for a matching If-None-Match, or the cached response; false when the job must run.
  bool answered_from_cache(const httplib::Request& req, httplib::Response& res, const std::string& etag) {
    if (req.get_header_value("If-None-Match") == etag) {
      res.status = 304;
      res.set_header("ETag", etag);
      return true;
    }
    if (auto hit = cache.get(etag)) {
      metrics.cache(true);
      for (const auto& [k, v] : hit->headers) res.set_header(k, v);
      res.set_header("X-ShadeLab-Cache", "hit");
      res.set_content(hit->body, hit->content_type);
      return true;
    }
    metrics.cache(false);
    return false;
  }

  void render(const httplib::Request& req, httplib::Response& res) {
    auto raw = read(req);
    if (!raw) return send_problem(res, raw.error(), req.path);
    auto parsed = parse_job(*raw, worker::JobKind::render, config.limits);
    if (!parsed) return send_problem(res, parsed.error(), req.path);
    worker::Message message;
    if (auto s = attach_mesh(*parsed, message); !s) return send_problem(res, s.error(), req.path);

    const std::string etag = etag_of(message, "");
    if (answered_from_cache(req, res, etag)) return;

    auto result = run(std::move(message));
    if (!result) return send_problem(res, result.error(), req.path);
    json& h = result->header;
    std::vector<std::string> warnings = parsed->warnings;
    for (const auto& w : h.value("warnings", json::array())) warnings.push_back(w);
    std::string constant;
    for (const auto& c : h.value("constantFrames", json::array())) {
      constant += (constant.empty() ? "" : ",") + std::to_string(c["frame"].get<int>());
      warnings.push_back("frame " + std::to_string(c["frame"].get<int>()) + " is one constant colour " + c["rgba"].dump() +
                         ": nothing was drawn, or the shader writes the same colour everywhere");
    }

    CachedResponse response;
    response.headers["ETag"] = etag;
    response.headers["Server-Timing"] = server_timing(h.value("timings", json::object()), result->queue_ms);
    response.headers["X-ShadeLab-Renderer"] = pool->renderer();
    response.headers["X-ShadeLab-Warnings"] = std::to_string(warnings.size());
    response.headers["Cache-Control"] = "no-cache";  // revalidate: the ETag makes that cheap
    if (!constant.empty()) response.headers["X-ShadeLab-Constant-Frames"] = constant;
    if (parsed->job.output == worker::Output::frames)
      response.headers["Content-Disposition"] = "attachment; filename=\"hw2_" + parsed->job.prefix + "_frames.zip\"";
    if (parsed->job.output == worker::Output::json) {
      json body = {{"renderer", pool->renderer()},
                   {"samples", h["samples"]},
                   {"warnings", warnings},
                   {"diagnostics", h["diagnostics"]},
                   {"constantFrames", h["constantFrames"]},
                   {"attributes", h["attributes"]},
                   {"uniforms", h["uniforms"]},
                   {"timings", h["timings"]},
                   {"images", h["images"]}};
      body["timings"]["queue"] = result->queue_ms;
      response.content_type = "application/json";
      response.body = body.dump(-1, ' ', false, json::error_handler_t::replace);
    } else {
      response.content_type = h.value("contentType", "application/octet-stream");
      response.body = std::move(result->payload);
    }
    for (const auto& [k, v] : response.headers) res.set_header(k, v);
    res.set_content(response.body, response.content_type);
    cache.put(etag, std::move(response));
  }

  void compile(const httplib::Request& req, httplib::Response& res) {
    auto raw = read(req);
    if (!raw) return send_problem(res, raw.error(), req.path);
    auto parsed = parse_job(*raw, worker::JobKind::compile, config.limits);
    if (!parsed) return send_problem(res, parsed.error(), req.path);
    worker::Message message{worker::to_json(parsed->job), {}};
    auto result = run(std::move(message));
    if (!result) return send_problem(res, result.error(), req.path);
    json& h = result->header;
    std::vector<std::string> warnings = parsed->warnings;
    for (const auto& w : h.value("warnings", json::array())) warnings.push_back(w);
    res.set_header("X-ShadeLab-Renderer", pool->renderer());
    send_json(res, 200, {{"ok", true}, {"renderer", pool->renderer()}, {"warnings", warnings},
                         {"diagnostics", h["diagnostics"]}, {"attributes", h["attributes"]}, {"uniforms", h["uniforms"]},
                         {"timings", h["timings"]}});
  }

  void grade(const httplib::Request& req, httplib::Response& res) {
    auto raw = read(req);
    if (!raw) return send_problem(res, raw.error(), req.path);
    // Read without throwing: these fields are type-checked by parse_grade_job, but its error path
    // below still needs them, whatever the client sent.
    const auto& fields = raw->fields;
    const std::string checkpoint = fields.contains("reference") && fields["reference"].is_string() ? fields["reference"].get<std::string>() : "custom";
    const std::string format = fields.contains("format") && fields["format"].is_string() ? fields["format"].get<std::string>() : "json";
    const double max_score = fields.contains("maxScore") && fields["maxScore"].is_number() ? fields["maxScore"].get<double>() : 1.0;
    auto parsed = parse_grade_job(*raw, config.limits);
    json result;
    std::string heatmap;
    double seconds = 0;
    if (!parsed) {
      // The submission's own source problems are its grade; a malformed request is not.
      const auto code = parsed.error().code;
      if (code != ErrorCode::shader_source_invalid && code != ErrorCode::missing_version)
        return send_problem(res, parsed.error(), req.path);
      result = grade::failed_submission(parsed.error(), checkpoint, max_score);
    } else {
      worker::Message message;
      if (auto s = attach_mesh(parsed->parsed, message); !s) return send_problem(res, s.error(), req.path);
      auto outcome = worker::grade_with_pool(*pool, parsed->parsed.job, message.payload);
      if (outcome.service_error) return send_problem(res, *outcome.service_error, req.path);
      result = std::move(outcome.result);
      heatmap = std::move(outcome.heatmap_png);
      seconds = outcome.seconds;
      for (const auto& w : parsed->parsed.warnings) result["warnings"].push_back(w);
    }
    if (format == "gradescope") return send_json(res, 200, grade::to_gradescope(result, seconds));
    if (!heatmap.empty()) result["heatmap"] = heatmap;
    send_json(res, 200, result);
  }

  // POST /api/scene: the scene as the JSON body, or multipart with the scene in the part "scene"
  // and mesh files in parts the objects name.
  void render_scene(const httplib::Request& req, httplib::Response& res) {
    json scene_json;
    std::map<std::string, UploadedFile> files;
    if (req.is_multipart_form_data()) {
      for (const auto& [name, part] : req.files) {
        if (name == "scene") scene_json = json::parse(part.content, nullptr, false);
        else files[name] = {part.filename, part.content};
      }
      if (!req.has_file("scene"))
        return send_problem(res, make_error(ErrorCode::invalid_argument, "send the scene JSON in the multipart part 'scene'"), req.path);
    } else {
      const std::string type = req.get_header_value("Content-Type");
      if (!type.empty() && type.find("json") == std::string::npos)
        return send_problem(res, make_error(ErrorCode::invalid_argument, "send the scene as JSON (Content-Type: application/json) or multipart/form-data; got " + type), req.path);
      scene_json = json::parse(req.body, nullptr, false);
    }
    if (scene_json.is_discarded())
      return send_problem(res, make_error(ErrorCode::invalid_argument, "the scene is not valid JSON"), req.path);
    auto description = scene::parse_scene(scene_json, config.limits.scene);
    if (!description) return send_problem(res, description.error(), req.path);

    worker::SceneJob job{scene_json, {}};
    std::set<std::string> attached;
    for (size_t i = 0; i < description->objects.size(); ++i) {
      const std::string& ref = description->objects[i].mesh;
      if (!attached.insert(ref).second) continue;
      if (auto f = files.find(ref); f != files.end()) {
        const auto dot = f->second.filename.find_last_of('.');
        job.meshes.push_back({ref, dot == std::string::npos ? "obj" : f->second.filename.substr(dot + 1), f->second.content});
      } else if (!scene::is_builtin_scene_mesh(ref)) {
        const auto stored = meshes.get(ref);
        if (!stored) {
          std::string builtins;
          for (const auto& n : scene::builtin_scene_mesh_names()) builtins += (builtins.empty() ? "" : ", ") + n;
          return send_problem(res, make_error(ErrorCode::mesh_not_found, "objects[" + std::to_string(i) + "].mesh: no mesh '" + ref +
                                                                              "' (built-ins: " + builtins + "; or an id from POST /api/meshes, or a multipart file part of that name)"),
                              req.path);
        }
        job.meshes.push_back({ref, stored->format, stored->bytes});
      }
    }
    worker::Message message = worker::to_message(job);
    const bool as_json = req.get_param_value("format") == "json" ||
                         (req.get_header_value("Accept").find("application/json") != std::string::npos &&
                          req.get_header_value("Accept").find("image/png") == std::string::npos);
    const std::string etag = etag_of(message, as_json ? "json" : "png");
    if (answered_from_cache(req, res, etag)) return;
    auto result = run(std::move(message));
    if (!result) return send_problem(res, result.error(), req.path);
    json report = result->header.value("report", json::object());

    CachedResponse response;
    response.headers["ETag"] = etag;
    response.headers["Cache-Control"] = "no-cache";
    response.headers["X-ShadeLab-Renderer"] = pool->renderer();
    response.headers["X-ShadeLab-Passes"] = scene_passes_header(report);
    response.headers["X-ShadeLab-Features"] = scene_features_header(report);
    response.headers["Server-Timing"] = "queue;dur=" + std::to_string(result->queue_ms) + ", " + scene_passes_header(report);
    if (!report.value("framing", json::array()).empty()) response.headers["X-ShadeLab-Framing"] = scene_framing_header(report);
    if (as_json) {
      report["renderer"] = pool->renderer();
      report["queueMs"] = result->queue_ms;
      report["encodeMs"] = result->header["timings"].value("encode", 0.0);
      report["image"] = OIIO::Strutil::base64_encode(result->payload);
      response.content_type = "application/json";
      response.body = report.dump(2, ' ', false, json::error_handler_t::replace);
    } else {
      response.content_type = "image/png";
      response.body = std::move(result->payload);
    }
    for (const auto& [k, v] : response.headers) res.set_header(k, v);
    res.set_content(response.body, response.content_type);
    cache.put(etag, std::move(response));
  }

  // GET /api/dolly?subject=0,0,0&from=0,-4,0&lens=25&lenses=25,50,100
  void dolly(const httplib::Request& req, httplib::Response& res) {
    const auto numbers = [&](const char* name, std::vector<double> fallback, size_t count) -> Expected<std::vector<double>> {
      if (!req.has_param(name)) return fallback;
      std::vector<double> out;
      const std::string text = req.get_param_value(name);
      size_t pos = 0;
      while (pos <= text.size()) {
        const size_t comma = std::min(text.find(',', pos), text.size());
        char* end = nullptr;
        const std::string item = text.substr(pos, comma - pos);
        const double v = std::strtod(item.c_str(), &end);
        if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v))
          return make_error(ErrorCode::invalid_argument, std::string(name) + ": '" + item + "' is not a number");
        out.push_back(v);
        pos = comma + 1;
      }
      if (count && out.size() != count) return make_error(ErrorCode::invalid_argument, std::string(name) + ": expected " + std::to_string(count) + " numbers");
      return out;
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
    for (const auto& s : scene::dolly_zoom({(*subject)[0], (*subject)[1], (*subject)[2]}, {(*from)[0], (*from)[1], (*from)[2]}, (*lens)[0], *lenses))
      stops.push_back({{"lens", s.lens_mm}, {"distance", s.distance}, {"location", {s.location.x, s.location.y, s.location.z}}});
    send_json(res, 200, {{"stops", stops}});
  }

  void upload_mesh(const httplib::Request& req, httplib::Response& res) {
    UploadedFile file;
    if (req.is_multipart_form_data()) {
      if (!req.has_file("mesh"))
        return send_problem(res, make_error(ErrorCode::invalid_argument, "send the mesh as the multipart file field 'mesh'"), req.path);
      const auto part = req.get_file_value("mesh");
      file = {part.filename, part.content};
    } else {
      file = {req.get_param_value("filename"), req.body};
      if (file.filename.empty()) file.filename = "mesh." + (req.has_param("format") ? req.get_param_value("format") : std::string("obj"));
    }
    if (file.content.empty()) return send_problem(res, make_error(ErrorCode::mesh_empty, "the mesh file is empty"), req.path);
    if (file.content.size() > config.limits.max_mesh_bytes)
      return send_problem(res, make_error(ErrorCode::payload_too_large, "the mesh file is too large"), req.path);
    const auto dot = file.filename.find_last_of('.');
    worker::Job job;
    job.kind = worker::JobKind::mesh_check;
    job.mesh = mesh_id(file.content);
    job.mesh_format = dot == std::string::npos ? "obj" : file.filename.substr(dot + 1);
    auto result = run({worker::to_json(job), file.content});
    if (!result) return send_problem(res, result.error(), req.path);
    json info = {{"triangles", result->header["triangles"]}, {"bounds", result->header["bounds"]},
                 {"normalsFromFile", result->header["normalsFromFile"]}};
    meshes.put({job.mesh, file.filename, job.mesh_format, file.content, info});
    send_json(res, 201, {{"id", job.mesh}, {"filename", file.filename}, {"format", job.mesh_format}, {"info", info}});
  }

  void routes() {
    server.Post("/api/render", [this](const auto& req, auto& res) { render(req, res); });
    server.Get("/api/render", [this](const auto& req, auto& res) { render(req, res); });
    server.Post("/api/compile", [this](const auto& req, auto& res) { compile(req, res); });
    server.Post("/api/grade", [this](const auto& req, auto& res) { grade(req, res); });
    server.Post("/api/meshes", [this](const auto& req, auto& res) { upload_mesh(req, res); });
    server.Post("/api/scene", [this](const auto& req, auto& res) { render_scene(req, res); });
    server.Get("/api/dolly", [this](const auto& req, auto& res) { dolly(req, res); });
    // The example scenes (assets/scenes/), ready to POST back to /api/scene.
    server.Get("/api/scenes", [](const auto&, auto& res) {
      json out = json::array();
      for (const auto& f : embedded_files())
        if (f.path.rfind("assets/scenes/", 0) == 0) {
          std::string name(f.path.substr(14));
          out.push_back(name.substr(0, name.size() - 5));
        }
      send_json(res, 200, {{"scenes", out}});
    });
    server.Get(R"(/api/scenes/([a-z0-9_]+))", [](const httplib::Request& req, httplib::Response& res) {
      const auto text = embedded_file("assets/scenes/" + std::string(req.matches[1]) + ".json");
      if (!text) return send_problem(res, make_error(ErrorCode::not_found, "no example scene '" + std::string(req.matches[1]) + "'"), req.path);
      res.set_content(std::string(*text), "application/json");
    });
    server.Get("/api/meshes", [this](const auto&, auto& res) {
      json builtin = json::array();
      for (const auto& n : scene::builtin_mesh_names()) builtin.push_back({{"id", n}, {"builtin", true}});
      json scene_builtin = json::array();
      for (const auto& n : scene::builtin_scene_mesh_names()) scene_builtin.push_back(n);
      send_json(res, 200, {{"builtin", builtin}, {"sceneBuiltin", scene_builtin}, {"uploaded", meshes.list()}});
    });
    // The built-in meshes as OBJ text, for the page's own WebGL canvas.
    server.Get(R"(/api/meshes/([a-z]+)\.obj)", [](const httplib::Request& req, httplib::Response& res) {
      const auto obj = embedded_file("assets/" + std::string(req.matches[1]) + ".obj");
      if (!obj) return send_problem(res, make_error(ErrorCode::mesh_not_found, "no built-in mesh '" + std::string(req.matches[1]) + "'"), req.path);
      res.set_header("Cache-Control", "public, max-age=3600");
      res.set_content(std::string(*obj), "text/plain; charset=utf-8");
    });
    server.Get("/api/presets", [](const auto&, auto& res) {
      json out = json::array();
      for (const auto& p : render::presets())
        out.push_back({{"name", p.name}, {"description", p.description},
                       {"vertex", {{"name", p.vertex.name}, {"source", p.vertex.text}}},
                       {"fragment", {{"name", p.fragment.name}, {"source", p.fragment.text}}}});
      send_json(res, 200, out);
    });
    server.Get("/api/openapi.json", [](const auto&, auto& res) {
      res.set_content(std::string(*embedded_file("docs/openapi.json")), "application/json");
    });
    server.Get("/livez", [](const auto&, auto& res) { send_json(res, 200, {{"status", "ok"}}); });
    server.Get("/readyz", [this](const auto&, auto& res) {
      const bool ready = pool->ready();
      if (!ready) res.set_header("Retry-After", "1");
      send_json(res, ready ? 200 : 503, {{"ready", ready}, {"renderer", pool->renderer()}});
    });
    server.Get("/metrics", [this](const auto&, auto& res) {
      res.set_content(metrics.render(pool->stats(), pool->ready()), "text/plain; version=0.0.4");
    });
    if (!config.web_root.empty() && !server.set_mount_point("/", config.web_root))
      std::fprintf(stderr, "shadelab: web root '%s' not found; serving the API only\n", config.web_root.c_str());

    server.set_pre_routing_handler([](const auto&, auto&) {
      request_start = Clock::now();
      return httplib::Server::HandlerResponse::Unhandled;
    });
    server.set_logger([this](const httplib::Request& req, const httplib::Response& res) {
      const std::string route = req.path.rfind("/api/", 0) == 0 || req.path == "/metrics" || req.path == "/livez" ||
                                        req.path == "/readyz"
                                    ? req.method + " " + req.path
                                    : "static";
      metrics.request(route, res.status, std::chrono::duration<double>(Clock::now() - request_start).count());
    });
    // Errors httplib raises itself (unknown route, body over the limit, unreadable request).
    server.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
      if (!res.body.empty()) return;
      const ErrorCode code = res.status == 413 ? ErrorCode::payload_too_large
                             : res.status == 404 ? ErrorCode::not_found
                                                 : ErrorCode::invalid_argument;
      Error e = make_error(code, res.status == 404 ? "no such resource: " + req.path
                                 : res.status == 413 ? "the request body is larger than the limit"
                                                     : "the request could not be read");
      const int status = res.status;
      send_problem(res, e, req.path);
      res.status = status;
    });
    server.set_exception_handler([](const httplib::Request& req, httplib::Response& res, std::exception_ptr ep) {
      std::string what = "internal error";
      try {
        std::rethrow_exception(ep);
      } catch (const std::exception& e) {
        what = e.what();
      } catch (...) {
      }
      send_problem(res, make_error(ErrorCode::io_error, what), req.path);
    });
  }
};

Service::Service(ServiceConfig config) : impl_(std::make_unique<Impl>(std::move(config))) {}
Service::~Service() { stop(); }

Expected<int> Service::start() {
  auto& i = *impl_;
  i.pool = std::make_unique<worker::WorkerPool>(i.config.pool);
  i.server.set_payload_max_length(i.config.limits.max_body_bytes);
  const int threads = i.config.http_threads;
  i.server.new_task_queue = [threads] { return new httplib::ThreadPool(static_cast<size_t>(threads)); };
  i.routes();
  i.port = i.config.port == 0 ? i.server.bind_to_any_port(i.config.host) : i.server.bind_to_port(i.config.host, i.config.port) ? i.config.port : -1;
  if (i.port <= 0)
    return make_error(ErrorCode::io_error, "cannot listen on " + i.config.host + ":" + std::to_string(i.config.port));
  i.thread = std::thread([&i] { i.server.listen_after_bind(); });
  return i.port;
}

void Service::stop() {
  if (!impl_) return;
  impl_->server.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
  impl_->pool.reset();
}

void Service::wait() {
  if (impl_->thread.joinable()) impl_->thread.join();
}

worker::WorkerPool& Service::pool() { return *impl_->pool; }

}  // namespace shadelab::http
