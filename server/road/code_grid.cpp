#include "road/code_grid.h"

#include <cmath>

#include "render/render_request.h"
#include "worker/client.h"
#include "worker/course_job.h"
#include "worker/result.h"

namespace shadelab::road {

GridJob course_grid_job(const course::Course& course, shader::ShaderFile vertex, shader::ShaderFile fragment, int frame_side) {
  GridJob out{worker::course_job(course, worker::JobKind::render, std::move(vertex), std::move(fragment)), {}};
  (void)worker::attach_course_mesh(course, course.default_mesh, out.job, out.payload);  // the default mesh is the course's own
  if (frame_side > 0 && out.job.request.width > 0) {
    const double scale = static_cast<double>(frame_side) / out.job.request.width;
    out.job.request.width = frame_side;
    out.job.request.height = std::max(1, static_cast<int>(std::lround(out.job.request.height * scale)));
  }
  return out;
}

Expected<std::string> render_grid(worker::WorkerPool& pool, GridJob job) {
  if (!render::check_sources(job.job.request, render::RenderLimits{})) return std::string();
  auto rendered = worker::run<worker::RenderResult>(pool, worker::to_message(job.job, std::move(job.payload)));
  if (rendered) return std::move(rendered->result.body);
  if (info(rendered.error().code).submission_caused) return std::string();
  return rendered.take_error();
}

}  // namespace shadelab::road
