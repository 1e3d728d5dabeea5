#include "http/route_context.h"

#include "core/hash.h"
#include "http/problem.h"
#include "http/session_key.h"
#include "scene/mesh.h"

namespace shadelab::http {

using nlohmann::json;

std::string json_text(const json& body, int indent) { return body.dump(indent, ' ', false, json::error_handler_t::replace); }

void add_route(httplib::Server& server, RouteContext& c, Method method, const std::string& pattern, RouteHandler handler) {
  auto with_viewer = [&c, handler = std::move(handler)](const httplib::Request& req, httplib::Response& res) {
    // A staff client grading for its students (a class batch through --server) asks to be answered
    // as a student is: `X-ShadeLab-View: student` lowers a request's view, never raises it.
    const bool as_student = req.get_header_value("X-ShadeLab-View") == "student";
    const course::Viewer viewer = as_student ? course::Viewer{} : course::Viewer{c.tenants.role_of(credential_of(req)), c.config.open_references};
    handler(c, viewer, req, res);
  };
  c.metrics.known_route(method == Method::get ? "GET" : "POST", pattern);
  if (method == Method::get) server.Get(pattern, std::move(with_viewer));
  else server.Post(pattern, std::move(with_viewer));
}

void send_problem(httplib::Response& res, const Error& e, const std::string& instance) {
  res.status = http_status(e.code);
  if (info(e.code).retry_later) res.set_header("Retry-After", "1");
  res.set_content(json_text(problem(e, instance)), "application/problem+json");
}

void send_json(httplib::Response& res, int status, const json& body) {
  res.status = status;
  res.set_content(json_text(body), "application/json");
}

Expected<std::string> RouteContext::mesh_bytes(ParsedJob& parsed) const {
  if (parsed.mesh_upload) return parsed.mesh_upload->bytes;
  if (!parsed.job.mesh_embedded.empty()) return std::string();
  if (!parsed.course_mesh_bytes.empty()) return std::move(parsed.course_mesh_bytes);
  auto stored = meshes.get(parsed.job.mesh);
  if (!stored) return stored.take_error();
  if (!*stored)
    return make_error(ErrorCode::mesh_not_found, "no mesh '" + parsed.job.mesh +
                                                     "': use one of the course's meshes (GET /api/course), or the id POST /api/meshes returned");
  parsed.job.mesh_format = (*stored)->format;
  return (*stored)->bytes;
}

Status RouteContext::find_uploaded_mesh(road::MeshChoice& mesh, const course::Course& course) const {
  if (mesh.upload || mesh.name.empty() || course.mesh(mesh.name)) return Ok{};
  auto stored = meshes.get(mesh.name);
  if (!stored) return stored.take_error();
  if (!*stored)
    return make_error(ErrorCode::mesh_not_found, "no mesh '" + mesh.name +
                                                     "': use one of the course's meshes (GET /api/course), or the id POST /api/meshes returned");
  mesh.upload = road::MeshChoice::Upload{mesh.name, (*stored)->format, (*stored)->bytes};
  return Ok{};
}

Status RouteContext::may_draw(const ParsedJob& parsed, const course::Course& course, const course::Viewer& viewer) const {
  if (!parsed.preset) return Ok{};
  auto found = course::find_visible_preset(course, parsed.preset->name, viewer);
  if (!found) return found.take_error();
  return Ok{};
}

const course::Course* RouteContext::course_param(const httplib::Request& req, httplib::Response& res) const {
  auto found = courses.named(req.has_param("course") ? req.get_param_value("course") : "");
  if (!found) {
    send_problem(res, found.error(), req.path);
    return nullptr;
  }
  return *found;
}

std::string RouteContext::etag_of(const worker::Message& job, const std::string& form) const {
  const std::string key = form + '\0' + json_text(job.header, -1) + '\0' + job.payload + '\0' + pool.renderer();
  // SHA-256, not FNV: with a shared store the key crosses tenants, and a crafted collision would
  // let one student's job be answered with another's response.
  return "\"" + sha256_hex(key).substr(0, 32) + "\"";
}

bool RouteContext::answered_from_cache(const httplib::Request& req, httplib::Response& res, const std::string& etag) {
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

void RouteContext::send_and_cache(httplib::Response& res, const std::string& etag, CachedResponse response) {
  response.headers["ETag"] = etag;
  response.headers["Cache-Control"] = "no-cache";  // revalidate: the ETag makes that cheap
  response.headers["X-ShadeLab-Renderer"] = pool.renderer();
  for (const auto& [k, v] : response.headers) res.set_header(k, v);
  res.set_content(response.body, response.content_type);
  cache.put(etag, std::move(response));
}

}  // namespace shadelab::http
