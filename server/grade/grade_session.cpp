#include "grade/grade_session.h"

#include <algorithm>
#include <memory>

#include "grade/diagnosis.h"
#include "grade/catalogue_reading.h"
#include "grade/formula_explanation.h"
#include "grade/formula_geometry.h"
#include "image/encode.h"
#include "image/grid.h"
#include "image/metrics.h"
#include "grade/starter_constants.h"

namespace shadelab::grade {

std::string GradeSession::heatmap_png(const SharedFrames& frames, const SharedFrames& reference, const render::RenderRequest& job) {
  std::vector<image::Image> heat;
  for (size_t k = 0; k < static_cast<size_t>(job.frames); ++k) heat.push_back(image::heatmap(*frames[k], *reference[k]));
  auto png = image::encode_png(image::compose_grid(image::GridLayout::for_frames(job.frames, job.width, job.height), heat));
  return png ? std::string(png->begin(), png->end()) : std::string();
}

Expected<SharedFrames> GradeSession::frames_of(const render::RenderRequest& r, const scene::Mesh& m) {
  SharedFrames out;
  auto rendered = renderer_.render(r, m, [&](int, const image::Image& f, bool) { out.push_back(std::make_shared<const image::Image>(f)); });
  if (!rendered) return rendered.take_error();
  return out;
}

void GradeSession::begin(const GradeSpec& spec) {
  work_ = {};
  store_.reset();
  if (spec.reference_store.empty()) return;
  const auto& info = renderer_.context_info();
  store_.emplace(spec.reference_store.folder, shared_store(spec.reference_store.shared), info.gl_renderer + " | " + info.gl_version);
}

store::SharedStore* GradeSession::shared_store(const store::SharedStoreConfig& config) {
  if (config.url.empty()) return nullptr;
  if (!shared_ || shared_config_ != config) {
    auto opened = store::SharedStore::open(config);
    shared_ = opened ? std::move(*opened) : nullptr;  // an address that does not parse: no sharing
    shared_config_ = config;
  }
  return shared_.get();
}

const std::string& GradeSession::mesh_address(const std::string& mesh_key, const scene::Mesh& mesh) {
  if (address_of_ != mesh_key) {
    address_ = scene::content_address(mesh);
    address_of_ = mesh_key;
  }
  return address_;
}

Expected<SharedFrames> GradeSession::stored_or_rendered(const render::RenderRequest& r, const scene::Mesh& m, const std::string& mesh_key) {
  const std::string stored = store_ ? store_->key(r, mesh_address(mesh_key, m)) : std::string();
  if (store_)
    if (auto loaded = store_->load(stored, r)) {
      ++work_.from_store;
      return std::move(*loaded);
    }
  auto frames = frames_of(r, m);
  if (!frames) return frames;
  ++work_.rendered;
  if (store_) store_->save(stored, *frames);
  return frames;
}

Expected<SharedFrames> GradeSession::cached_frames(const render::RenderRequest& r, const scene::Mesh& m, const std::string& mesh_key) {
  std::string key = render::pixel_identity(r) + '\0' + mesh_key;
  if (const SharedFrames* hit = references_.find(key)) {
    ++work_.from_memory;
    return *hit;
  }
  auto frames = stored_or_rendered(r, m, mesh_key);
  if (frames) references_.insert(std::move(key), *frames);
  return frames;
}

std::vector<RenderedMistake> GradeSession::rendered_mistakes(const GradeSpec& spec, const std::vector<const Mistake*>& which,
                                                             const render::RenderRequest& reference, const scene::Mesh& mesh,
                                                             const std::string& mesh_key) {
  std::vector<RenderedMistake> mistakes;
  for (const Mistake* mk : which) {
    render::RenderRequest mr = reference;
    mr.vertex = mk->vertex;
    mr.fragment = mk->fragment;
    if (auto frames = cached_under_lights(spec, mr, mesh, mesh_key)) mistakes.push_back({mk->id, mk->message, std::move(*frames)});
  }
  return mistakes;
}

// `base` under the probe's light, for the names the program declares as the page does; a name
// declared otherwise stays as the homework sets it, as in the browser.
Expected<render::RenderRequest> GradeSession::with_light(const GradeSpec& spec, const render::RenderRequest& base, const Probe& probe) {
  auto program = renderer_.compile(base.vertex, base.fragment);
  if (!program) return program.take_error();
  render::RenderRequest lit = base;
  for (auto& s : probe_settings(spec, probe)) {
    const bool declared = std::any_of(program->uniforms.begin(), program->uniforms.end(),
                                      [&](const auto& u) { return u.name == s.name && u.type == s.type && u.array_size == 1; });
    const bool set = std::any_of(lit.uniforms.begin(), lit.uniforms.end(), [&](const auto& u) { return u.name == s.name; });
    if (declared && !set) lit.uniforms.push_back({s.name, std::move(s.value)});
  }
  return lit;
}

// A submission right under the page's light and wrong only under probe lights is told which, and
// what each checks, in the course's words: the probe is the explanation ("the light's colour
// multiplies both terms").
static void name_probes_that_fail(Report& report, const std::vector<Probe>& probes) {
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

const std::vector<model::FrameSurface>* GradeSession::surfaces(const FormulaSpec& formula, const render::RenderRequest& reference,
                                                              const scene::Mesh& mesh, const std::string& mesh_key, GeometryKept kept,
                                                              SampleGeometry samples) {
  auto requests = geometry_requests(formula, reference, samples);
  if (!requests) return nullptr;
  const auto key_of = [&](auto begin, auto end) {
    std::string key = mesh_key;
    for (auto g = begin; g != end; ++g) key += '\0' + render::pixel_identity(g->request);
    return key;
  };
  std::string key = key_of(requests->begin(), requests->end());
  if (auto* hit = surfaces_.find(key)) {
    ++work_.from_memory;
    return hit;
  }
  // A render at a time, each turned into the object's pixels before the next: the float frames
  // are ten times the surfaces' size. The samples start from the averaged geometry where this
  // worker holds it (the grade that asks for them has just read it).
  std::vector<model::FrameSurface> out;
  auto first = std::find_if(requests->begin(), requests->end(), [](const GeometryRender& g) { return g.quantity == model::Quantity::sample_flat_normal; });
  if (const auto* averaged = first != requests->end() ? surfaces_.find(key_of(requests->begin(), first)) : nullptr)
    out = *averaged;
  else
    first = requests->begin();
  for (auto it = first; it != requests->end(); ++it) {
    const auto& [request, quantity, sample] = *it;
    auto frames = kept == GeometryKept::with_references ? stored_or_rendered(request, mesh, mesh_key) : frames_of(request, mesh);
    if (!frames) return nullptr;
    if (kept == GeometryKept::in_memory) ++work_.rendered;
    for (std::size_t k = 0; k < frames->size(); ++k) {
      if (quantity == model::Quantity::position) out.push_back(model::surface_from(*(*frames)[k]));
      else if (k < out.size()) model::add_quantity(out[k], *(*frames)[k], quantity, sample);
    }
  }
  std::size_t bytes = 0;
  for (const auto& s : out) bytes += s.bytes();
  return &surfaces_.insert(std::move(key), std::move(out), bytes);
}

std::function<const std::vector<model::FrameSurface>*()> GradeSession::sampled_surfaces(const FormulaSpec& formula,
                                                                                      const render::RenderRequest& reference,
                                                                                      const scene::Mesh& mesh, const std::string& mesh_key,
                                                                                      GeometryKept kept) {
  if (!has_sample_geometry(formula, reference)) return {};
  return [this, &formula, reference, &mesh, mesh_key, kept] { return surfaces(formula, reference, mesh, mesh_key, kept, SampleGeometry::each_sample); };
}

std::optional<Explanation> GradeSession::formula_explanation(const GradeSpec& spec, const render::RenderRequest& reference,
                                                              const scene::Mesh& mesh, const std::string& mesh_key,
                                                              const SharedFrames& student, const SharedFrames& reference_frames) {
  if (!spec.formula) return std::nullopt;
  const auto* geometry = surfaces(*spec.formula, reference, mesh, mesh_key, GeometryKept::with_references);
  if (!geometry) return std::nullopt;
  return explain_with_formula({&*spec.formula, reference.uniforms, spec.probes, geometry, &student, &reference_frames,
                               sampled_surfaces(*spec.formula, reference, mesh, mesh_key, GeometryKept::with_references)},
                              spec.options)
      .explanation;
}

// `base` under the homework's light, then under each probe light.
Expected<std::vector<render::RenderRequest>> GradeSession::under_lights(const GradeSpec& spec, const render::RenderRequest& base) {
  std::vector<render::RenderRequest> lit = {base};
  for (const auto& probe : spec.probes) {
    auto moved = with_light(spec, base, probe);
    if (!moved) return moved.take_error();
    lit.push_back(std::move(*moved));
  }
  return lit;
}

// A reference's or a mistake's frames, under the homework's light and then each probe light,
// light by light through the caches.
Expected<SharedFrames> GradeSession::cached_under_lights(const GradeSpec& spec, const render::RenderRequest& base,
                                                         const scene::Mesh& mesh, const std::string& cache_key) {
  auto lit = under_lights(spec, base);
  if (!lit) return lit.take_error();
  SharedFrames all;
  for (const auto& r : *lit) {
    auto frames = cached_frames(r, mesh, cache_key);
    if (!frames) return frames.take_error();
    all.insert(all.end(), frames->begin(), frames->end());
  }
  return all;
}

// The submission under every light, drawn together (Renderer::render_together), with the census
// of its colours: the NaN and infinities the canvas would store as 0 or clamp.
Expected<GradeSession::SubmissionFrames> GradeSession::submission_under_lights(const GradeSpec& spec,
                                                                               const render::RenderRequest& base,
                                                                               const scene::Mesh& mesh) {
  auto lit = under_lights(spec, base);
  if (!lit) return lit.take_error();
  std::vector<SharedFrames> frames(lit->size());
  std::vector<std::vector<image::NonFinite>> counts(lit->size());
  auto rendered = renderer_.render_together(
      *lit, mesh, [&](int i, int, const image::Image& f, bool) { frames[static_cast<size_t>(i)].push_back(std::make_shared<const image::Image>(f)); },
      [&](int i, int, const image::NonFinite& n) { counts[static_cast<size_t>(i)].push_back(n); });
  if (!rendered) return rendered.take_error();
  SubmissionFrames out;
  for (size_t i = 0; i < lit->size(); ++i) {
    out.frames.insert(out.frames.end(), frames[i].begin(), frames[i].end());
    out.non_finite.insert(out.non_finite.end(), counts[i].begin(), counts[i].end());
  }
  return out;
}

Expected<GradeOutput> GradeSession::grade(const GradeSpec& spec, const render::RenderRequest& submission, const MeshSource& mesh_source,
                                          const std::string& mesh_key, const EnterPhase& enter) {
  const auto ungradable = [&](const Error& e) { return GradeOutput{failed_submission(e, spec.reference_name, spec.options.max_score), {}}; };
  begin(spec);
  auto compiled = renderer_.compile(submission.vertex, submission.fragment);
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
  auto student = submission_under_lights(spec, r, **mesh);
  if (!student && (student.error().code == ErrorCode::compile_failed || student.error().code == ErrorCode::link_failed)) {
    render::RenderRequest as_compiled = r;
    as_compiled.semantics = render::FloatSemantics::as_compiled;
    student = submission_under_lights(spec, as_compiled, **mesh);
  }
  if (!student) return ungradable(student.error());
  if (auto s = enter(JobPhase::grader); !s) return s.take_error();

  // The reference gets the same uniform values as the submission: a grader that changes the
  // colours grades against the reference with those colours.
  render::RenderRequest ref = r;
  ref.vertex = spec.reference_vertex;
  ref.fragment = spec.reference_fragment;
  auto reference = cached_under_lights(spec, ref, **mesh, mesh_key);
  if (!reference) return make_error(ErrorCode::invalid_argument, "the reference does not render: " + reference.error().message);
  // The formula and the catalogue only for a submission that fails: a passing one needs no
  // diagnosis. The formula first: a known mistake it reads needs no render (catalogue_work).
  GradeResult result = assess(student->frames, student->non_finite, *reference, spec.options);
  std::optional<Explanation> explanation;
  if (!result.pass) {
    explanation = formula_explanation(spec, ref, **mesh, mesh_key, student->frames, *reference);
    const CatalogueWork catalogue = catalogue_work(spec.mistakes, explanation);
    const auto recognised = recognised_mistake(catalogue);
    explain(result, student->frames, *reference, rendered_mistakes(spec, catalogue.to_render, ref, **mesh, mesh_key), spec.options,
            recognised ? &*recognised : nullptr);
  }

  std::vector<std::string> lights = {"homework"};
  for (const auto& p : spec.probes) lights.push_back(p.name);
  GradeOutput out{report(result, spec.reference_name, lights, static_cast<size_t>(r.frames)), {}};
  out.report.grader_work = work_;
  out.report.warnings = compiled->warnings;
  if (!out.report.pass && out.report.diagnosis.empty()) name_probes_that_fail(out.report, spec.probes);
  // A catalogued mistake says what went wrong already; otherwise a changed starter constant may.
  if (!out.report.pass && out.report.diagnosis.empty())
    for (const auto& found : changed_starter_constants(spec.starter_constants, submission.fragment.text)) {
      if (out.report.diagnosis.empty()) out.report.diagnosis = changed_constant_diagnosis(found.variable);
      out.report.messages.insert(out.report.messages.begin(), found.message);
    }
  out.report.explanation = std::move(explanation);
  say_explanation(out.report);
  if (spec.wants_heatmap(out.report.pass)) out.heatmap_png = heatmap_png(student->frames, *reference, r);  // the homework light's
  return out;
}

}  // namespace shadelab::grade
