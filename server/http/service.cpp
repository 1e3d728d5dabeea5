#include "http/service.h"

#include <httplib.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <optional>

#include "http/memory_stream.h"
#include "http/route_context.h"
#include "http/session_key.h"

namespace shadelab::http {

namespace {

using Clock = std::chrono::steady_clock;

thread_local Clock::time_point request_start;

// Every response, the page's first: script only from this server's own files (no inline script,
// no blob: or data: script, no eval), so a student's text that reached the page as a module could
// not run even if a regression imported it; images may be data: and blob: (the page draws PNGs the
// API returns, and fetches a frame's data: URL to compare it; neither reaches another host); no framing, no plugins, no form posted elsewhere; no type sniffing.
const httplib::Headers kSecurityHeaders = {
    {"Content-Security-Policy",
     "default-src 'self'; script-src 'self'; style-src 'self'; img-src 'self' data: blob:; connect-src 'self' data: blob:; "
     "object-src 'none'; base-uri 'none'; form-action 'self'; frame-ancestors 'none'"},
    {"X-Content-Type-Options", "nosniff"},
    {"Referrer-Policy", "no-referrer"},
};

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

// API keys and rates apply to the API; probes, metrics and the page's files are always served.
bool admit(Tenants& tenants, const TenantLimits& limits, const httplib::Request& req, httplib::Response& res) {
  if (req.path.rfind("/api/", 0) != 0) return true;
  const std::string client = client_address(req.remote_addr, req.get_header_value("X-Forwarded-For"), limits.trusted_proxies);
  const auto verdict = tenants.admit(credential_of(req), client);
  if (!verdict.refused) return true;
  send_problem(res, *verdict.refused, req.path);
  if (verdict.refused->code == ErrorCode::rate_limited) {
    res.headers.erase("Retry-After");  // the wait this tenant has, not the generic second
    res.set_header("Retry-After", std::to_string(verdict.retry_after_seconds));
  }
  if (verdict.refused->code == ErrorCode::unauthorized) res.set_header("WWW-Authenticate", "Bearer");
  return false;
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

// The connection layer reads bodies, so it holds them to the same limit as the routes.
ServiceConfig with_body_limit(ServiceConfig c) {
  c.connections.framing.max_body_bytes = c.limits.max_body_bytes;
  return c;
}

std::unique_ptr<store::SharedStore> open_shared(const store::SharedStoreConfig& config, std::optional<Error>& error) {
  if (config.url.empty()) return nullptr;
  auto opened = store::SharedStore::open(config);
  if (!opened) {
    error = opened.take_error();
    return nullptr;
  }
  return std::move(*opened);
}

// httplib's routing and request parsing, run on a request the connection layer read whole.
class RequestProcessor : public httplib::Server {
 public:
  OutgoingResponse process(const IncomingRequest& request) {
    OutgoingResponse response;
    MemoryStream stream(request, response.bytes);
    bool client_closes = false;
    const bool ok = process_request(stream, request.last, client_closes, nullptr);
    response.close = !ok || client_closes || request.last;
    return response;
  }
};

}  // namespace

struct Service::Impl {
  ServiceConfig config;
  RequestProcessor server;
  ConnectionServer connections;
  std::unique_ptr<worker::WorkerPool> pool;
  std::unique_ptr<store::SharedStore> shared;
  std::optional<Error> shared_error;  // a malformed --redis, reported by start()
  MeshStore meshes;
  ResponseCache cache;
  Metrics metrics;
  std::optional<Tenants> tenants;
  std::optional<RouteContext> context;
  std::mutex mutex;
  std::condition_variable stopped_changed;
  bool stopped = false;

  explicit Impl(ServiceConfig c)
      : config(with_body_limit(std::move(c))),
        connections(config.connections, [this](IncomingRequest r) { return server.process(r); }),
        shared(open_shared(config.shared_store, shared_error)),
        meshes(config.limits.max_stored_meshes, shared.get()),
        cache(config.cache_bytes, shared.get()) {}

  void routes() {
    context.emplace(RouteContext{config, config.courses, *pool, meshes, cache, metrics, connections, *tenants, shared.get()});
    add_render_routes(server, *context);
    add_grade_routes(server, *context);
    add_sheet_routes(server, *context);
    add_scene_routes(server, *context);
    add_mesh_routes(server, *context);
    add_session_routes(server, *context);
    add_service_routes(server, *context);
    server.set_default_headers(kSecurityHeaders);
    if (!config.web_root.empty() && !server.set_mount_point("/", config.web_root))
      std::fprintf(stderr, "shadelab: web root '%s' not found; serving the API only\n", config.web_root.c_str());

    server.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
      request_start = Clock::now();
      return admit(*tenants, config.tenants, req, res) ? httplib::Server::HandlerResponse::Unhandled : httplib::Server::HandlerResponse::Handled;
    });
    server.set_logger([this](const httplib::Request& req, const httplib::Response& res) {
      metrics.request(metrics.route_label(req.method, req.path), res.status, std::chrono::duration<double>(Clock::now() - request_start).count());
    });
    server.set_error_handler(answer_httplib_error);
    server.set_exception_handler(answer_exception);
  }
};

Service::Service(ServiceConfig config) : impl_(std::make_unique<Impl>(std::move(config))) {}
Service::~Service() { stop(); }

Expected<int> Service::start() {
  auto& i = *impl_;
  if (i.shared_error) return *i.shared_error;
  if (auto ranges = check_address_ranges(i.config.tenants.trusted_proxies); !ranges) return ranges.take_error();
  // The port first: a server that cannot listen starts no workers.
  std::vector<ApiKey> keys;
  if (i.config.tenants.students_without_keys && i.config.tenants.api_keys_file.empty())
    return make_error(ErrorCode::invalid_argument,
                      "--students-without-keys is for a server with --api-keys (without a keys file every caller is a student already)");
  if (!i.config.tenants.api_keys_file.empty()) {
    auto read = read_api_keys(i.config.tenants.api_keys_file);
    if (!read) return read.take_error();
    keys = std::move(*read);
  }
  i.tenants.emplace(i.config.tenants, std::move(keys));
  auto port = i.connections.listen(i.config.host, i.config.port);
  if (!port) return port;
  i.pool = std::make_unique<worker::WorkerPool>(i.config.pool);
  i.server.set_payload_max_length(i.config.limits.max_body_bytes);
  // Only what httplib writes in its Keep-Alive header: the connection layer enforces both.
  i.server.set_keep_alive_max_count(static_cast<size_t>(i.config.connections.keep_alive_requests));
  i.server.set_keep_alive_timeout(std::max<time_t>(1, i.config.connections.keep_alive_idle.count() / 1000));
  i.routes();
  i.connections.start();
  return port;
}

void Service::stop() {
  if (!impl_) return;
  impl_->connections.stop();
  impl_->context.reset();
  impl_->pool.reset();
  {
    std::lock_guard lock(impl_->mutex);
    impl_->stopped = true;
  }
  impl_->stopped_changed.notify_all();
}

void Service::wait() {
  std::unique_lock lock(impl_->mutex);
  impl_->stopped_changed.wait(lock, [this] { return impl_->stopped; });
}

worker::WorkerPool& Service::pool() { return *impl_->pool; }

}  // namespace shadelab::http
