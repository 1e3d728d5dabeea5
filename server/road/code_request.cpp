#include "road/code_request.h"

#include "core/words.h"
#include "worker/course_job.h"

namespace shadelab::road {

namespace {

// The student's shaders, or the preset's when the request names one the viewer may see.
Expected<ShaderPair> shaders_of(const course::Course& c, const CodeRequest& request, const course::Viewer& viewer,
                                std::vector<std::string>& warnings) {
  if (request.preset.empty()) return *request.code;
  auto found = course::find_visible_preset(c, request.preset, viewer);
  if (!found) return found.take_error();
  if (found->alias) warnings.push_back(found->alias->note);
  return ShaderPair{found->preset->vertex, found->preset->fragment};
}

// The course's request with the client's changes.
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

Status attach_mesh(const course::Course& c, MeshChoice mesh, CodeSubmission& out) {
  if (!mesh.upload) return worker::attach_course_mesh(c, mesh.name.empty() ? c.default_mesh : mesh.name, out.render, out.mesh_bytes);
  out.render.mesh = std::move(mesh.upload->id);
  out.render.mesh_format = std::move(mesh.upload->format);
  out.mesh_bytes = std::move(mesh.upload->bytes);
  return Ok{};
}

// The page's own reference: graded at the course's tolerance, out of 1.
grade::GradeSpec own_reference_spec(const course::Course& c, ShaderPair reference) {
  grade::GradeSpec spec;
  spec.reference_name = "custom";
  spec.reference_vertex = std::move(reference.vertex);
  spec.reference_fragment = std::move(reference.fragment);
  spec.light_position_uniforms = c.light_position_names();
  spec.light_color_uniform = c.light_color_uniform();
  spec.options = c.tolerance;
  spec.options.max_score = 1;
  return spec;
}

// The spec graded against, and the words of its checkpoint's vectors (`vectors`).
Expected<grade::GradeSpec> spec_of(const course::Course& c, CodeRequest& request, std::vector<std::string>& warnings, grade::VectorWords& vectors) {
  if (request.reference.empty() == !request.own_reference)
    return make_error(ErrorCode::invalid_argument, "give either 'reference' (a checkpoint: " + comma_list(c.checkpoint_names()) +
                                                       ") or 'referenceVertex' and 'referenceFragment'");
  if (request.own_reference) return own_reference_spec(c, std::move(*request.own_reference));
  auto found = c.checkpoint(request.reference);
  if (!found) return found.take_error();
  if (found->alias) warnings.push_back(found->alias->note);
  vectors = vector_words(*found->checkpoint);
  return c.grade_spec(*found->checkpoint, c.grade_options(*found->checkpoint));
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

// Here rather than beside course_code: the request's parsers are built without the road's pool
// (tests/fuzz), and both need it.
grade::VectorWords vector_words(const course::Checkpoint& checkpoint) {
  grade::VectorWords out;
  if (checkpoint.formula)
    for (const auto& [vector, local] : checkpoint.formula->vectors) out.emplace(local, name_in(grade::kFormulaVectorWords, vector));
  return out;
}

Expected<BuiltCode> code_submission(const course::Course& c, CodeRequest request, const course::Viewer& viewer,
                                    const render::RenderLimits& limits) {
  std::vector<std::string> warnings;
  auto shaders = shaders_of(c, request, viewer, warnings);
  if (!shaders) return shaders.take_error();
  BuiltCode out{{worker::course_job(c, worker::JobKind::grade, std::move(shaders->vertex), std::move(shaders->fragment)), {}, {}, limits},
                std::move(warnings)};
  if (auto s = shape_render(c, request.render, out.submission.render); !s) return s.take_error();
  if (auto s = attach_mesh(c, std::move(request.mesh), out.submission); !s) return s.take_error();
  if (auto valid = render::validate(out.submission.render.request, limits); !valid) return valid.take_error();
  auto spec = spec_of(c, request, out.warnings, out.submission.vector_words);
  if (!spec) return spec.take_error();
  if (auto s = apply_tolerance(request.tolerance, spec->options); !s) return s.take_error();
  out.submission.spec = std::move(*spec);
  out.submission.repair_shown = viewer.sees_references() ? repair::RepairShown::repaired_line : c.repair_shown;
  if (viewer.sees_references()) out.submission.spec.picture = grade::DifferencePicture::full;
  return out;
}

}  // namespace shadelab::road
