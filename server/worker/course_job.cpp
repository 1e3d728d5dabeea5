#include "worker/course_job.h"

namespace shadelab::worker {

Job course_job(const course::Course& c, JobKind kind, shader::ShaderFile vertex, shader::ShaderFile fragment) {
  Job job;
  job.kind = kind;
  job.request = c.render_request(std::move(vertex), std::move(fragment));
  job.frame_name = c.frame_name;
  return job;
}

Status attach_course_mesh(const course::Course& c, const std::string& name, Job& job, std::string& payload) {
  const course::CourseMesh* m = c.mesh(name);
  if (!m) {
    std::string names;
    for (const auto& n : c.mesh_names()) names += (names.empty() ? "" : ", ") + n;
    return make_error(ErrorCode::mesh_not_found, "no mesh '" + name + "' in " + c.id + " (its meshes: " + names + ")");
  }
  job.mesh = m->id;
  job.mesh_embedded = m->embedded ? m->id : "";
  job.mesh_format = m->format;
  payload = m->embedded ? std::string() : m->bytes;
  return Ok{};
}

}  // namespace shadelab::worker
