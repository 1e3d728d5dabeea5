#pragma once
// What every route module shares: the service's state, one reader for request bodies, the
// problem+json and JSON writers, the ETag cache, and the metrics of a worker's answer. Each
// resource's routes live in their own file (render_routes, grade_routes, scene_routes,
// mesh_routes, service_routes) and register themselves on the server.
#include <httplib.h>

#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "course/access.h"
#include "http/api_request.h"
#include "http/request_reader.h"
#include "http/mesh_store.h"
#include "http/metrics.h"
#include "http/response_cache.h"
#include "http/service.h"
#include "road/code_request.h"
#include "worker/client.h"

namespace shadelab::http {

struct RouteContext {
  const ServiceConfig& config;
  const course::CourseSet& courses;
  worker::WorkerPool& pool;
  MeshStore& meshes;
  ResponseCache& cache;
  Metrics& metrics;
  const ConnectionServer& connections;
  Tenants& tenants;
  store::SharedStore* shared;  // null without --redis

  // A compile failure, or a driver that refused what the browser runs, in the metrics.
  void count(const Error& e) const {
    if (e.code == ErrorCode::compile_failed || e.code == ErrorCode::link_failed) metrics.compile_failure();
    if (e.code == ErrorCode::driver_refused) metrics.driver_refusal();
  }

  // Runs a job and records its queue time (and a compile failure) in the metrics.
  template <class Result>
  Expected<worker::Answered<Result>> run(worker::Message job) {
    auto answered = worker::run<Result>(pool, std::move(job));
    if (!answered) {
      count(answered.error());
    } else {
      metrics.phase("queue", answered->queue_ms / 1000);
    }
    return answered;
  }

  // The bytes of the job's mesh: a file in this request, a course's own mesh, an uploaded id (its
  // format set on the job), or none for a mesh compiled into the binary.
  Expected<std::string> mesh_bytes(ParsedJob& parsed) const;

  // A mesh named by an id POST /api/meshes returned (not one of the course's meshes): set as the
  // choice's upload; mesh_not_found when there is no such upload.
  Status find_uploaded_mesh(road::MeshChoice& mesh, const course::Course& course) const;

  // Whether `viewer` may have what `parsed` draws: a reference preset only with a staff key.
  Status may_draw(const ParsedJob& parsed, const course::Course& course, const course::Viewer& viewer) const;

  // The course `?course=ID` names, or the default one; null, with the problem answered, otherwise.
  const course::Course* course_param(const httplib::Request& req, httplib::Response& res) const;

  // Same job, same mesh bytes, same renderer, same response form: same bytes out. That makes a
  // strong ETag.
  std::string etag_of(const worker::Message& job, const std::string& form) const;
  // A 304 for a matching If-None-Match, or the cached response; false when the job must run.
  bool answered_from_cache(const httplib::Request& req, httplib::Response& res, const std::string& etag);
  // Sends `response` and keeps it under `etag`.
  void send_and_cache(httplib::Response& res, const std::string& etag, CachedResponse response);
};

// Every route's handler is given who asks (course/access.h) where it is registered: the role of the
// request's key, and the server's openness. No route is staff-only; what a response holds follows
// the viewer, and a handler cannot forget to ask: a request without a staff key is a student's.
using RouteHandler = std::function<void(RouteContext&, const course::Viewer&, const httplib::Request&, httplib::Response&)>;
enum class Method { get, post };
void add_route(httplib::Server& server, RouteContext& context, Method method, const std::string& pattern, RouteHandler handler);

void send_problem(httplib::Response& res, const Error& e, const std::string& instance);
void send_json(httplib::Response& res, int status, const nlohmann::json& body);
std::string json_text(const nlohmann::json& body, int indent = 2);

void add_render_routes(httplib::Server& server, RouteContext& context);   // /api/render, /api/compile
void add_grade_routes(httplib::Server& server, RouteContext& context);    // /api/grade
void add_sheet_routes(httplib::Server& server, RouteContext& context);    // /api/sheet
void add_scene_routes(httplib::Server& server, RouteContext& context);    // /api/scene, /api/scenes, /api/dolly
void add_mesh_routes(httplib::Server& server, RouteContext& context);     // /api/meshes
void add_session_routes(httplib::Server& server, RouteContext& context);  // /api/session: the page's key as a cookie
void add_service_routes(httplib::Server& server, RouteContext& context);  // presets, OpenAPI, health, metrics

}  // namespace shadelab::http
