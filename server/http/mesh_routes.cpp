// /api/meshes: uploads (checked by a worker, where assimp runs), the list, and the built-ins as
// OBJ text for the page's own WebGL canvas.
#include "core/embedded_files.h"
#include "http/route_context.h"
#include "scene/mesh.h"
#include "scene/scene_mesh.h"

namespace shadelab::http {

namespace {

using nlohmann::json;

// The mesh file of an upload: the multipart file field "mesh", or the raw body named by
// ?filename= (or ?format=).
Expected<UploadedFile> read_mesh_upload(const httplib::Request& req, const Limits& limits) {
  UploadedFile file;
  if (req.is_multipart_form_data()) {
    if (!req.has_file("mesh")) return make_error(ErrorCode::invalid_argument, "send the mesh as the multipart file field 'mesh'");
    const auto part = req.get_file_value("mesh");
    file = {part.filename, part.content};
  } else {
    file = {req.get_param_value("filename"), req.body};
    if (file.filename.empty()) file.filename = "mesh." + (req.has_param("format") ? req.get_param_value("format") : std::string("obj"));
  }
  if (file.content.empty()) return make_error(ErrorCode::mesh_empty, "the mesh file is empty");
  if (file.content.size() > limits.max_mesh_bytes) return make_error(ErrorCode::payload_too_large, "the mesh file is too large");
  return file;
}

void upload(RouteContext& c, const course::Viewer&, const httplib::Request& req, httplib::Response& res) {
  auto file = read_mesh_upload(req, c.config.limits);
  if (!file) return send_problem(res, file.error(), req.path);
  worker::Job job;
  job.kind = worker::JobKind::mesh_check;
  job.mesh = mesh_id(file->content);
  job.mesh_format = scene::mesh_format_of(file->filename);
  auto answered = c.run<worker::MeshCheckResult>(worker::to_message(job, file->content));
  if (!answered) return send_problem(res, answered.error(), req.path);
  const json info = answered->result;
  c.meshes.put({job.mesh, file->filename, job.mesh_format, std::move(file->content), info});
  send_json(res, 201, {{"id", job.mesh}, {"filename", file->filename}, {"format", job.mesh_format}, {"info", info}});
}

void list(RouteContext& c, const course::Viewer&, const httplib::Request& req, httplib::Response& res) {
  const course::Course* course = c.course_param(req, res);
  if (!course) return;
  json builtin = json::array(), scene_builtin = json::array();
  for (const auto& n : course->mesh_names()) builtin.push_back({{"id", n}, {"builtin", true}});
  for (const auto& n : scene::builtin_scene_mesh_names()) scene_builtin.push_back(n);
  // Uploads are not listed: an upload's id is the capability to use it, known to its uploader only.
  send_json(res, 200, {{"course", course->id}, {"builtin", builtin}, {"sceneBuiltin", scene_builtin}});
}

// A course's mesh as the page loads it: the OBJ file's bytes, as the course hands them out.
void course_obj(RouteContext& c, const course::Viewer&, const httplib::Request& req, httplib::Response& res) {
  const course::Course* course = c.course_param(req, res);
  if (!course) return;
  const std::string name = req.matches[1];
  const course::CourseMesh* mesh = course->mesh(name);
  if (!mesh) return send_problem(res, make_error(ErrorCode::mesh_not_found, "no mesh '" + name + "' in " + course->id), req.path);
  res.set_header("Cache-Control", "public, max-age=3600");
  res.set_content(mesh->embedded ? std::string(*embedded_file(mesh->id)) : mesh->bytes, "text/plain; charset=utf-8");
}

}  // namespace

void add_mesh_routes(httplib::Server& server, RouteContext& c) {
  add_route(server, c, Method::post, "/api/meshes", upload);
  add_route(server, c, Method::get, "/api/meshes", list);
  add_route(server, c, Method::get, R"(/api/meshes/([a-z0-9_-]+)\.obj)", course_obj);
}

}  // namespace shadelab::http
