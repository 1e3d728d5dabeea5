// judge_saved_frames: the frames a student saved from their browser, graded against the
// reference at the lag each was drawn with, and against their own code at the same angles.
//
// The work, for a deliverable of 9 frames: the reference at the lag grid's angles (65 frames,
// once per course: the store and the worker's memory keep it), the lags fitted against it, then
// the reference rendered once at the fitted angles (one render of the job) and compared. Only a
// failing set pays for more: the formula's geometry at the angles the frames' outlines fit, for
// the explanation (three float renders for a lit checkpoint, and four more, one a sample, where a
// specular one's flat shading could be what the frames show; four for the normal's colour: the
// position, the normal, the colour interpolated and flat), kept in memory only: no other student's
// frames are drawn at those angles; and a known mistake the formula does not read, rendered at the
// same angles, for the diagnosis.
#include "grade/judge_saved_frames.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "grade/catalogue_reading.h"
#include "grade/formula_explanation.h"
#include "grade/lag_fit.h"
#include "grade/saved_frames_verdicts.h"
#include "image/metrics.h"
#include "image/png_decode.h"

namespace shadelab::grade {

namespace {

// The saved frames decoded, each the canvas's size; frames_invalid naming the file otherwise.
Expected<SharedFrames> decode_all(const std::vector<SavedFrame>& saved, int width, int height) {
  SharedFrames out;
  for (const auto& f : saved) {
    auto image = image::decode_png(f.bytes);
    if (!image) return make_error(ErrorCode::frames_invalid, f.name + ": " + image.error().message);
    if (image->width != width || image->height != height)
      return make_error(ErrorCode::frames_invalid, f.name + " is " + std::to_string(image->width) + " x " + std::to_string(image->height) +
                                                       "; the course's canvas is " + std::to_string(width) + " x " + std::to_string(height) +
                                                       ": save the frames from the page at its own size");
    out.push_back(std::make_shared<const image::Image>(std::move(*image)));
  }
  return out;
}

// The angle each frame was drawn at, to a thousandth of a degree (what a render is keyed by).
std::vector<double> fitted_angles(const std::vector<LagFit>& fits, const LagGrid& grid) {
  std::vector<double> out;
  for (const auto& f : fits) out.push_back(std::round((grid.nominal(f.frame) - f.lag_degrees) * 1000) / 1000);
  return out;
}

// The reference as the student's page drew it (the page's own uniform values), at every angle of
// the lag grid.
render::RenderRequest reference_grid(const GradeSpec& spec, const render::RenderRequest& code, const LagGrid& grid) {
  render::RenderRequest ref = code;
  ref.uniforms.clear();
  ref.vertex = spec.reference_vertex;
  ref.fragment = spec.reference_fragment;
  ref.angles = grid.angles();
  ref.frames = static_cast<int>(ref.angles.size());
  ref.pixel_type = image::PixelType::u8;
  return ref;
}

// Frames from another rasteriser (the student's browser): an edge may fall a pixel away, and the
// outline's pixels be covered differently.
GradeOptions saved_frames_options(GradeOptions options) {
  options.compare.spatial_tolerance = true;
  options.compare.outline_tolerance = true;
  options.closer_than_reference = options.saved_frames_closer_than_reference;
  return options;
}

// Failing saved frames read by the formula: on the geometry at the angles their outlines fit
// (grade/lag_fit.h's fit_outline_lags: shading of another kind misleads the reference's fit),
// against the reference rendered at the same angles, under the saved frames' `options`.
struct SavedFramesReading {
  Explanation explanation;
  // The angles it read the frames at: their outlines' fit, moved where placed by their edges.
  std::vector<LagFit> fits;
};

// `which` of the known mistakes (catalogue_work's), compared with a failing set of saved frames,
// each at the angles the frames fit it at (`fits` says which mistake's, when not the reference's).
struct MistakesAtLags {
  std::vector<RenderedMistake> rendered;
  std::vector<std::pair<std::string, std::vector<LagFit>>> fits;
};

std::optional<SavedFramesReading> saved_frames_explanation(GradeRenders& renders, const GradeSpec& spec, const GradeOptions& options,
                                                                  const render::RenderRequest& grid_request,
                                                                  const scene::Mesh& mesh, const std::string& mesh_key, const SharedFrames& saved,
                                                                  const SharedFrames& grid_frames, const LagGrid& grid) {
  if (!spec.formula) return std::nullopt;
  std::vector<const image::Image*> images;
  for (const auto& f : saved) images.push_back(f.get());
  // The angles each frame was drawn at, refined between the grid's steps, and the reference and
  // the geometry rendered there (one render more than the grid's frames at their nearest step):
  // shading that changes sharply with the angle (flat normals, an exponent under 1) moves by more
  // than the threshold in the twentieth of a degree between them.
  std::vector<LagFit> fits = fit_outline_lags(images, grid_frames, grid);
  render::RenderRequest at = grid_request;
  at.angles = fitted_angles(fits, grid);
  at.frames = static_cast<int>(at.angles.size());
  auto reference = renders.at_angles(grid_request, mesh, at.angles);
  if (!reference) return std::nullopt;
  const auto* geometry = renders.surfaces(*spec.formula, at, mesh, mesh_key, GeometryKept::in_memory);
  if (!geometry) return std::nullopt;
  FormulaRead read = explain_with_formula({&*spec.formula, at.uniforms, {}, geometry, &saved, &*reference,
                                           renders.sampled_surfaces(*spec.formula, at, mesh, mesh_key, GeometryKept::in_memory),
                                           renders.moved_flat_colour(*spec.formula, at, mesh)},
                                          options);
  // A page draws at or behind a frame's angle: an edge's move past it (frame 0's, by a few ten-
  // thousandths of a degree) is the placement's scatter.
  for (std::size_t k = 0; k < fits.size() && k < at.angles.size(); ++k)
    fits[k].lag_degrees = std::max(0.0, grid.nominal(fits[k].frame) - at.angles[k] - (k < read.angle_moves.size() ? read.angle_moves[k] : 0.0));
  return SavedFramesReading{std::move(read.explanation), std::move(fits)};
}

// Every mistake is rendered at the angles fitted against the reference; those that explain the
// frames best there (better than the reference, and within twice the best mistake's residual) are
// fitted on their own lag grid (frames of other shading fit the reference's grid at the wrong
// angles: the shading, not the rotation, decides the fit) and rendered again at their own angles.
// Most mistakes are ruled out by one render of the job.
MistakesAtLags mistakes_at_lags(GradeRenders& renders, const std::vector<const Mistake*>& which, const render::RenderRequest& grid_request,
                                                            const scene::Mesh& mesh, const std::string& mesh_key,
                                                            const std::vector<const image::Image*>& saved, const std::vector<LagFit>& fits,
                                                            const LagGrid& grid) {
  const std::vector<double> angles = fitted_angles(fits, grid);
  struct Candidate {
    const Mistake* mistake;
    render::RenderRequest request;
    SharedFrames frames;
    double residual = 0;
  };
  std::vector<Candidate> candidates;
  double best = total_residual(fits);
  for (const Mistake* mk : which) {
    render::RenderRequest mr = grid_request;
    mr.vertex = mk->vertex;
    mr.fragment = mk->fragment;
    auto at = renders.at_angles(mr, mesh, angles);
    if (!at) continue;  // a catalogued mistake that does not render diagnoses nothing
    double residual = 0;
    for (size_t k = 0; k < saved.size(); ++k) residual += squared_difference(*saved[k], *(*at)[k]);
    best = std::min(best, residual);
    candidates.push_back({mk, std::move(mr), std::move(*at), residual});
  }
  const double reference_residual = total_residual(fits);
  MistakesAtLags out;
  for (auto& c : candidates) {
    if (c.residual < reference_residual && c.residual <= 2 * best)
      if (auto own_grid = renders.cached_frames(c.request, mesh, mesh_key)) {
        std::vector<LagFit> own = fit_lags(saved, *own_grid, grid);
        if (auto refit = renders.at_angles(c.request, mesh, fitted_angles(own, grid))) {
          c.frames = std::move(*refit);
          out.fits.emplace_back(c.mistake->id, std::move(own));
        }
      }
    out.rendered.push_back({c.mistake->id, c.mistake->message, std::move(c.frames)});
  }
  return out;
}

}  // namespace

Expected<FramesGradeOutput> judge_saved_frames(GradeRenders& renders, const GradeSpec& spec, const render::RenderRequest& code, const std::vector<SavedFrame>& saved,
                                                       const MeshSource& mesh_source, const std::string& mesh_key, const EnterPhase& enter) {
  renders.begin(spec);
  const auto failed = [&](const Error& e) { return FramesGradeOutput{failed_submission(e, spec.reference_name, spec.options.max_score), {}, {}}; };
  // The student's code first, under the compile deadline; its failure is the code's report.
  const bool has_code = !code.vertex.text.empty() || !code.fragment.text.empty();
  std::optional<Error> code_error;
  if (has_code)
    if (auto compiled = renders.renderer().compile(code.vertex, code.fragment); !compiled) code_error = compiled.error();
  if (auto s = enter(JobPhase::grader); !s) return s.take_error();
  auto frames = decode_all(saved, code.width, code.height);
  if (!frames) return failed(frames.error());
  if (frames->size() != static_cast<size_t>(code.frames))
    return failed(make_error(ErrorCode::frames_invalid, std::to_string(frames->size()) + " frames handed in; the deliverable has " +
                                                            std::to_string(code.frames)));
  auto mesh = mesh_source();
  if (!mesh) return mesh.take_error();

  const LagGrid grid{code.frames, code.degrees_per_frame};
  const render::RenderRequest ref = reference_grid(spec, code, grid);
  auto grid_frames = renders.cached_frames(ref, **mesh, mesh_key);
  if (!grid_frames) return make_error(ErrorCode::invalid_argument, "the reference does not render: " + grid_frames.error().message);
  std::vector<const image::Image*> saved_images;
  for (const auto& f : *frames) saved_images.push_back(f.get());
  const std::vector<LagFit> fits = fit_lags(saved_images, *grid_frames, grid);
  const std::vector<double> angles = fitted_angles(fits, grid);
  auto reference = renders.at_angles(ref, **mesh, angles);
  if (!reference) return make_error(ErrorCode::invalid_argument, "the reference does not render: " + reference.error().message);

  const GradeOptions options = saved_frames_options(spec.options);
  GradeResult result = grade::assess(*frames, {}, *reference, options);
  std::vector<LagFit> diagnosed_fits = fits;
  std::optional<Explanation> explanation;
  if (!result.pass) {
    // The formula first (a known mistake it reads needs no render), for frames of the mesh's
    // shape in their own order: it reads shading, not rotations or outlines.
    const bool in_order = std::none_of(fits.begin(), fits.end(), [](const LagFit& f) { return f.looks_like.has_value(); });
    // Frames the formula reads are described at the angles it read them at: the reference's fit
    // follows their shading, which is not the reference's.
    if (in_order && worst_outline_overlap(*frames, *reference) >= options.same_outline)
      if (auto read = saved_frames_explanation(renders, spec, options, ref, **mesh, mesh_key, *frames, *grid_frames, grid)) {
        if (read->explanation.explained) diagnosed_fits = std::move(read->fits);
        explanation = std::move(read->explanation);
      }
    const CatalogueWork catalogue = catalogue_work(spec.mistakes, explanation);
    const auto recognised = recognised_mistake(catalogue);
    MistakesAtLags mistakes = mistakes_at_lags(renders, catalogue.to_render, ref, **mesh, mesh_key, saved_images, fits, grid);
    explain(result, *frames, *reference, mistakes.rendered, options, recognised ? &*recognised : nullptr);
    for (const auto& [id, own] : mistakes.fits)
      if (id == result.diagnosis) diagnosed_fits = own;
  }
  FramesGradeOutput out{report(result, spec.reference_name, {"homework"}, fits.size()), {}, {}};
  describe_fits(diagnosed_fits, grid, saved, out.frames);
  if (!result.pass && out.frames.diagnosis.empty()) say_if_another_shape(out.frames, *frames, *reference, options);
  settle(out.frames);
  judge_provenance(out.frames, saved_images, *grid_frames, grid, diagnosed_fits, spec.frames_from_page);
  if (!out.frames.pass) {
    out.frames.explanation = std::move(explanation);
    say_explanation(out.frames);
  }

  if (has_code && code_error) out.code = failed_submission(*code_error, spec.reference_name, spec.options.max_score);
  if (has_code && !code_error) {
    render::RenderRequest at = code;
    at.angles = angles;
    at.pixel_type = image::PixelType::u8;
    if (auto s = enter(JobPhase::render); !s) return s.take_error();
    auto rendered = renders.frames_of(at, **mesh);
    if (auto s = enter(JobPhase::grader); !s) return s.take_error();
    out.code = rendered ? code_match(*frames, *rendered, *reference, out.frames, spec, options)
                        : failed_submission(rendered.error(), spec.reference_name, spec.options.max_score);
  }
  out.frames.grader_work = renders.work();
  if (spec.wants_heatmap(out.frames.pass)) out.heatmap_png = heatmap_png(*frames, *reference, code, spec);
  return out;
}

}  // namespace shadelab::grade
