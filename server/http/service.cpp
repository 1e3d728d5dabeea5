#include "http/service.h"

#include <httplib.h>

#include <chrono>
#include <cstdio>
#include <optional>
#include <thread>

#include "http/route_context.h"

namespace shadelab::http {

namespace {

using Clock = std::chrono::steady_clock;

thread_local Clock::time_point request_start;

// The route a request is counted under in the metrics: the API's own paths, or "static".
std::string metrics_route(const httplib::Request& req) {
  const bool api = req.path.rfind("/api/", 0) == 0 || req.path == "/metrics" || req.path == "/livez" || req.path == "/readyz";
  return api ? req.method + " " + req.path : "static";
}

// Errors httplib raises itself (unknown route, body over the limit, unreadable request).
void answer_httplib_error(const httplib::Request& req, httplib::Response& res) {
  if (!res.body.empty()) return;
  const int status = res.status;
  const ErrorCode code = status == 413 ? ErrorCode::payload_too_large : status == 404 ? ErrorCode::not_found : ErrorCode::invalid_argument;
  const std::string message = status == 404   ? "no such resource: " + req.path
                              : status == 413 ? "the request body is larger than the limit"
                                              : "the request could not be read";
  send_problem(res, make_error(code, message), req.path);
  res.status = status;
}

void answer_exception(const httplib::Request& req, httplib::Response& res, std::exception_ptr ep) {
  std::string what = "internal error";
  try {
    std::rethrow_exception(ep);
  } catch (const std::exception& e) {
    what = e.what();
  } catch (...) {
  }
  send_problem(res, make_error(ErrorCode::io_error, what), req.path);
}

}  // namespace

struct Service::Impl {
  ServiceConfig config;
  httplib::Server server;
  std::unique_ptr<worker::WorkerPool> pool;
  MeshStore meshes;
  ResponseCache cache;
  Metrics metrics;
  std::optional<RouteContext> context;
  std::thread thread;

  explicit Impl(ServiceConfig c) : config(std::move(c)), meshes(config.limits.max_stored_meshes), cache(config.cache_bytes) {}

  void routes() {
    context.emplace(RouteContext{config, *pool, meshes, cache, metrics});
    add_render_routes(server, *context);
    add_grade_routes(server, *context);
    add_scene_routes(server, *context);
    add_mesh_routes(server, *context);
    add_service_routes(server, *context);
    if (!config.web_root.empty() && !server.set_mount_point("/", config.web_root))
      std::fprintf(stderr, "shadelab: web root '%s' not found; serving the API only\n", config.web_root.c_str());

    server.set_pre_routing_handler([](const httplib::Request&, httplib::Response&) {
      request_start = Clock::now();
      return httplib::Server::HandlerResponse::Unhandled;
    });
    server.set_logger([this](const httplib::Request& req, const httplib::Response& res) {
      metrics.request(metrics_route(req), res.status, std::chrono::duration<double>(Clock::now() - request_start).count());
    });
    server.set_error_handler(answer_httplib_error);
    server.set_exception_handler(answer_exception);
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
  const int port = i.config.port == 0 ? i.server.bind_to_any_port(i.config.host)
                   : i.server.bind_to_port(i.config.host, i.config.port) ? i.config.port
                                                                          : -1;
  if (port <= 0) return make_error(ErrorCode::io_error, "cannot listen on " + i.config.host + ":" + std::to_string(i.config.port));
  i.thread = std::thread([&i] { i.server.listen_after_bind(); });
  return port;
}

void Service::stop() {
  if (!impl_) return;
  impl_->server.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
  impl_->context.reset();
  impl_->pool.reset();
}

void Service::wait() {
  if (impl_->thread.joinable()) impl_->thread.join();
}

worker::WorkerPool& Service::pool() { return *impl_->pool; }

}  // namespace shadelab::http
