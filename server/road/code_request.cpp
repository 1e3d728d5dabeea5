#include "road/code_request.h"

#include "worker/course_job.h"

namespace shadelab::road {

namespace {

// The course's render with the client's changes.
Status shape_render(const course::Course& c, const RenderShape& shape, worker::Job& job) {
  auto& r = job.request;
  r.width = shape.width.value_or(r.width);
  r.height = shape.height.value_or(r.height);
  r.frames = shape.frames.value_or(r.frames);
  r.msaa = shape.msaa.value_or(r.msaa);
  r.degrees_per_frame = shape.degrees_per_frame.value_or(r.degrees_per_frame);
  r.uniforms = shape.uniforms;
  if (!shape.fit) return Ok{};
  auto target = course::fit_bounds(c);
  if (!target) return target.take_error();
  job.fit = *target;
  return Ok{};
}

// The course's mesh the answer names, or the one the client uploaded.
void attach_mesh(const course::CourseMesh* course_mesh, MeshChoice mesh, CodeSubmission& out) {
  if (course_mesh) return worker::attach_mesh(*course_mesh, out.render, out.mesh_bytes);
  out.render.mesh = std::move(mesh.upload->id);
  out.render.mesh_format = std::move(mesh.upload->format);
  out.mesh_bytes = std::move(mesh.upload->bytes);
}

Status apply_tolerance(const ToleranceShape& t, grade::GradeOptions& options) {
  const double threshold = t.threshold.value_or(options.compare.threshold);
  const double failing = t.max_failing_fraction.value_or(options.max_failing_fraction);
  const double max_score = t.max_score.value_or(options.max_score);
  if (threshold < 0 || threshold > 1 || failing < 0 || failing > 1 || max_score < 0)
    return make_error(ErrorCode::invalid_argument, "'threshold' and 'maxFailingFraction' must be in [0, 1], 'maxScore' not negative");
  options.compare.threshold = threshold;
  options.max_failing_fraction = failing;
  options.max_score = max_score;
  options.compare.spatial_tolerance = t.spatial_tolerance;
  return Ok{};
}

}  // namespace

Expected<BuiltCode> code_submission(const course::Course& c, CodeRequest request, const course::Viewer& viewer,
                                    const render::RenderLimits& limits) {
  course::CodeQuestion question{std::move(request.code), request.preset, request.reference, std::move(request.own_reference), {}};
  if (!request.mesh.upload) question.mesh = request.mesh.name;
  auto asked = course::answer(c, std::move(question), viewer);
  if (!asked) return asked.take_error();
  BuiltCode out{{worker::course_job(c, worker::JobKind::grade, std::move(asked->request)), {}, std::move(asked->spec), limits},
                std::move(asked->notes)};
  CodeSubmission& s = out.submission;
  s.vector_words = std::move(asked->vectors);
  if (auto shaped = shape_render(c, request.render, s.render); !shaped) return shaped.take_error();
  attach_mesh(asked->mesh, std::move(request.mesh), s);
  if (auto valid = render::validate(s.render.request, limits); !valid) return valid.take_error();
  if (auto t = apply_tolerance(request.tolerance, s.spec.options); !t) return t.take_error();
  s.repair_shown = viewer.sees_references() ? repair::RepairShown::repaired_line : c.repair_shown;
  if (viewer.sees_references()) s.spec.picture = grade::DifferencePicture::full;
  return out;
}

}  // namespace shadelab::road
