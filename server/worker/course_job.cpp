#include "worker/course_job.h"

namespace shadelab::worker {

Job course_job(const course::Course& c, JobKind kind, shader::ShaderFile vertex, shader::ShaderFile fragment) {
  return course_job(c, kind, c.render_request(std::move(vertex), std::move(fragment)));
}

Job course_job(const course::Course& c, JobKind kind, render::RenderRequest request) {
  Job job;
  job.kind = kind;
  job.request = std::move(request);
  job.frame_name = c.frame_name;
  return job;
}

Status attach_course_mesh(const course::Course& c, const std::string& name, Job& job, std::string& payload) {
  auto m = c.find_mesh(name);
  if (!m) return m.take_error();
  attach_mesh(**m, job, payload);
  return Ok{};
}

void attach_mesh(const course::CourseMesh& m, Job& job, std::string& payload) {
  job.mesh = m.id;
  job.mesh_embedded = m.embedded ? m.id : "";
  job.mesh_format = m.format;
  payload = m.embedded ? std::string() : m.bytes;
}

}  // namespace shadelab::worker
