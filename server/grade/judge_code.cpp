#include "grade/judge_code.h"

#include <algorithm>
#include <optional>
#include <vector>

#include "grade/catalogue_reading.h"
#include "grade/diagnosis.h"
#include "grade/formula_explanation.h"
#include "grade/starter_constants.h"

namespace shadelab::grade {

namespace {

// A submission right under the page's light and wrong only under probe lights is told which, and
// what each checks, in the course's words: the probe is the explanation ("the light's colour
// multiplies both terms").
void name_probes_that_fail(Report& report, const std::vector<Probe>& probes) {
  const auto failing = [&](const std::string& light) {
    return std::count_if(report.frames.begin(), report.frames.end(), [&](const FrameReport& f) { return f.light == light && !f.grade.pass; });
  };
  if (failing("homework") > 0) return;
  std::vector<std::string> said;
  for (const auto& p : probes)
    if (const auto n = failing(p.name); n > 0) {
      const auto of = std::count_if(report.frames.begin(), report.frames.end(), [&](const FrameReport& f) { return f.light == p.name; });
      said.push_back("right under the page's light, not under the probe light " + p.name + " (" + std::to_string(n) + " of " +
                     std::to_string(of) + " frames differ)" + (p.checks.empty() ? "" : ", which checks that " + p.checks));
    }
  report.messages.insert(report.messages.begin(), said.begin(), said.end());
}

// The reference drawn with a request's uniform values failed. A student may not learn the
// reference's uniforms from it ("'uSpecularColor' is a vec3 in the shader"): a wrong value says only
// that the reference could not be drawn with it; the reference's other failures are the grader's.
Error reference_not_drawn(const Error& e) {
  if (e.code == ErrorCode::uniform_type_mismatch)
    return make_error(ErrorCode::invalid_argument,
                      "the reference cannot be drawn with the uniform values sent: send only uniforms your shaders declare, each "
                      "with as many numbers as its type holds");
  return make_error(ErrorCode::invalid_argument, "the reference does not render: " + e.message);
}

// A failing submission's frames read by the checkpoint's formula (grade/formula_explanation.h),
// on the geometry of `reference` (rendered once per course, kept as references are); none when
// the spec has no formula or the geometry does not render.
std::optional<Explanation> formula_explanation(GradeRenders& renders, const GradeSpec& spec, const render::RenderRequest& reference,
                                                              const scene::Mesh& mesh, const std::string& mesh_key,
                                                              const SharedFrames& student, const SharedFrames& reference_frames) {
  if (!spec.formula) return std::nullopt;
  const auto* geometry = renders.surfaces(*spec.formula, reference, mesh, mesh_key, GeometryKept::with_references);
  if (!geometry) return std::nullopt;
  return explain_with_formula({&*spec.formula, reference.uniforms, spec.probes, geometry, &student, &reference_frames,
                               renders.sampled_surfaces(*spec.formula, reference, mesh, mesh_key, GeometryKept::with_references)},
                              spec.options)
      .explanation;
}

// `shadelab course warm` (GradeSpec::warm): every render a failing grade of the checkpoint may
// read, made now and kept with the references, whatever this grade itself needed: which of them
// a student's grade reads depends on their frames (the formula's reading, the catalogue's), and a
// warm that read only its own submission's left the rest to the first student who needed them.
void warm_the_store(GradeRenders& renders, const GradeSpec& spec, const render::RenderRequest& reference, const scene::Mesh& mesh,
                    const std::string& mesh_key) {
  if (spec.formula && renders.surfaces(*spec.formula, reference, mesh, mesh_key, GeometryKept::with_references))
    if (const auto each_sample = renders.sampled_surfaces(*spec.formula, reference, mesh, mesh_key, GeometryKept::with_references)) each_sample();
  std::vector<const Mistake*> every;
  for (const auto& m : spec.mistakes) every.push_back(&m);
  renders.rendered_mistakes(spec, every, reference, mesh, mesh_key);
}

// The student's fragment values against the reference's (GradeSpec::read_values), under the
// page's light and each probe light the student's frames fail under: a value right under the
// page's white light may leave its colour out.
repair::ValueAgreement values_read(GradeRenders& renders, const GradeSpec& spec, const render::RenderRequest& submission,
                                   const render::RenderRequest& reference, const scene::Mesh& mesh, const Report& report) {
  auto student = renders.under_lights(spec, submission);
  auto theirs = renders.under_lights(spec, reference);
  if (!student || !theirs || student->size() != theirs->size() || student->size() != spec.probes.size() + 1) return {};
  std::vector<render::RenderRequest> s, t;
  for (size_t i = 0; i < student->size(); ++i) {
    const std::string light = i == 0 ? "homework" : spec.probes[i - 1].name;
    const bool fails = std::any_of(report.frames.begin(), report.frames.end(), [&](const FrameReport& f) { return f.light == light && !f.grade.pass; });
    if (i > 0 && !fails) continue;
    s.push_back(std::move((*student)[i]));
    t.push_back(std::move((*theirs)[i]));
  }
  return read_values(renders.renderer(), s, t, mesh);
}

}  // namespace

Expected<GradeOutput> judge_code(GradeRenders& renders, const GradeSpec& spec, const render::RenderRequest& submission, const MeshSource& mesh_source,
                                          const std::string& mesh_key, const EnterPhase& enter) {
  // What the student's shaders caused is their grade (0, with the reason); what they did not (a
  // driver that refuses what the browser runs) is the grader's failure, never the student's 0.
  const auto ungradable = [&](const Error& e) -> Expected<GradeOutput> {
    if (!info(e.code).submission_caused) return e;
    return GradeOutput{failed_submission(e, spec.reference_name, spec.options.max_score), {}};
  };
  renders.begin(spec);
  auto compiled = renders.renderer().compile(submission.vertex, submission.fragment);
  if (!compiled) return ungradable(compiled.error());
  if (auto s = enter(JobPhase::render); !s) return s.take_error();
  auto mesh = mesh_source();
  if (!mesh) return mesh.take_error();

  // Everything the grade compares is drawn with IEEE arithmetic: the census then finds a NaN that
  // Mesa's optimiser would fold away and the student's GPU may not (docs/grading.md). If the
  // driver does not take the invariant outputs, the submission is graded as compiled.
  render::RenderRequest r = submission;
  r.pixel_type = image::PixelType::u8;
  r.semantics = render::FloatSemantics::ieee;
  auto student = renders.submission_under_lights(spec, r, **mesh);
  if (!student && student.error().code == ErrorCode::driver_refused) {
    render::RenderRequest as_compiled = r;
    as_compiled.semantics = render::FloatSemantics::as_compiled;
    student = renders.submission_under_lights(spec, as_compiled, **mesh);
  }
  if (!student) return ungradable(student.error());
  if (auto s = enter(JobPhase::grader); !s) return s.take_error();

  // The reference gets the same uniform values as the submission: a grader that changes the
  // colours grades against the reference with those colours.
  render::RenderRequest ref = r;
  ref.vertex = spec.reference_vertex;
  ref.fragment = spec.reference_fragment;
  auto reference = renders.cached_under_lights(spec, ref, **mesh, mesh_key);
  if (!reference) return reference_not_drawn(reference.error());
  if (spec.warm) warm_the_store(renders, spec, ref, **mesh, mesh_key);
  // The formula and the catalogue only for a submission that fails: a passing one needs no
  // diagnosis. The formula first: a known mistake it reads needs no render (catalogue_work).
  GradeResult result = assess(student->frames, student->non_finite, *reference, spec.options);
  std::optional<Explanation> explanation;
  if (!result.pass) {
    explanation = formula_explanation(renders, spec, ref, **mesh, mesh_key, student->frames, *reference);
    const CatalogueWork catalogue = catalogue_work(spec.mistakes, explanation);
    const auto recognised = recognised_mistake(catalogue);
    explain(result, student->frames, *reference, renders.rendered_mistakes(spec, catalogue.to_render, ref, **mesh, mesh_key), spec.options,
            recognised ? &*recognised : nullptr);
  }

  std::vector<std::string> lights = {"homework"};
  for (const auto& p : spec.probes) lights.push_back(p.name);
  GradeOutput out{report(result, spec.reference_name, lights, static_cast<size_t>(r.frames)), {}};
  out.report.grader_work = renders.work();
  out.report.warnings = compiled->warnings;
  if (!out.report.pass && out.report.diagnosis.empty()) name_probes_that_fail(out.report, spec.probes);
  // A catalogued mistake says what went wrong already; otherwise a changed starter constant may.
  if (!out.report.pass && out.report.diagnosis.empty())
    for (const auto& found : changed_starter_constants(spec.starter_constants, submission.fragment.text)) {
      if (out.report.diagnosis.empty()) out.report.diagnosis = changed_constant_diagnosis(found.variable);
      out.report.messages.insert(out.report.messages.begin(), found.message);
    }
  if (spec.read_values && !out.report.pass) out.values = values_read(renders, spec, r, ref, **mesh, out.report);
  out.report.explanation = std::move(explanation);
  say_explanation(out.report);
  if (spec.wants_heatmap(out.report.pass)) out.heatmap_png = heatmap_png(student->frames, *reference, r, spec);  // the homework light's
  return out;
}

}  // namespace shadelab::grade
