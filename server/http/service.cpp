#include "http/service.h"

#include <httplib.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include "core/embedded_files.h"
#include "grade/report.h"
#include "http/api_request.h"
#include "worker/grade_client.h"
#include "http/mesh_store.h"
#include "http/metrics.h"
#include "http/problem.h"
#include "http/response_cache.h"
#include "render/presets.h"
#include "scene/mesh.h"

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

  void render(const httplib::Request& req, httplib::Response& res) {
    auto raw = read(req);
    if (!raw) return send_problem(res, raw.error(), req.path);
    auto parsed = parse_job(*raw, worker::JobKind::render, config.limits);
    if (!parsed) return send_problem(res, parsed.error(), req.path);
    worker::Message message;
    if (auto s = attach_mesh(*parsed, message); !s) return send_problem(res, s.error(), req.path);

    // Same job, same mesh bytes, same renderer: same bytes out. That makes a strong ETag.
    const std::string key = message.header.dump(-1, ' ', false, json::error_handler_t::replace) + '\0' + message.payload + '\0' + pool->renderer();
    const std::string etag = "\"" + hex(fnv1a64(key)) + hex(fnv1a64(key, 0x9e3779b97f4a7c15ull)) + "\"";
    if (req.get_header_value("If-None-Match") == etag) {
      res.status = 304;
      res.set_header("ETag", etag);
      return;
    }
    if (auto hit = cache.get(etag)) {
      metrics.cache(true);
      for (const auto& [k, v] : hit->headers) res.set_header(k, v);
      res.set_header("X-ShadeLab-Cache", "hit");
      res.set_content(hit->body, hit->content_type);
      return;
    }
    metrics.cache(false);

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
    server.Get("/api/meshes", [this](const auto&, auto& res) {
      json builtin = json::array();
      for (const auto& n : scene::builtin_mesh_names()) builtin.push_back({{"id", n}, {"builtin", true}});
      send_json(res, 200, {{"builtin", builtin}, {"uploaded", meshes.list()}});
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
