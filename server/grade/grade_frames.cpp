// GradeSession::grade_frames: the frames a student saved from their browser, graded against the
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
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/words.h"
#include "grade/diagnosis.h"
#include "grade/catalogue_reading.h"
#include "grade/formula_explanation.h"
#include "grade/grade_session.h"
#include "grade/lag_fit.h"
#include "grade/provenance.h"
#include "image/encode.h"
#include "image/grid.h"
#include "image/metrics.h"
#include "image/png_decode.h"

namespace shadelab::grade {

namespace {

std::string degrees(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}


std::string frame_list(const std::vector<int>& frames) {
  std::vector<std::string> numbers;
  for (int k : frames) numbers.push_back(std::to_string(k));
  return and_list(numbers);
}

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

// How much two frames' outlines overlap: the pixels either covers that both cover.
double outline_overlap(const image::Image& a, const image::Image& b) {
  size_t both = 0, either = 0;
  for (size_t i = 0; i < a.bytes.size(); i += 4) {
    const bool in_a = !is_clear(&a.bytes[i]), in_b = !is_clear(&b.bytes[i]);
    both += in_a && in_b;
    either += in_a || in_b;
  }
  return either == 0 ? 1 : static_cast<double>(both) / static_cast<double>(either);
}

// The lowest outline overlap over the frames: under GradeOptions::same_outline the saved frames
// show another shape (another mesh, another camera) than the one rendered, whatever the shading.
double worst_outline_overlap(const SharedFrames& a, const SharedFrames& b) {
  double worst = 1;
  for (size_t k = 0; k < a.size(); ++k) worst = std::min(worst, outline_overlap(*a[k], *b[k]));
  return worst;
}

// Whether frames 1 on were drawn at exactly their nominal angles: what a page with a fixed clock gives.
bool without_lag(const std::vector<LagFit>& fits) {
  if (fits.size() < 2) return false;
  for (size_t k = 1; k < fits.size(); ++k)
    if (fits[k].lag_degrees >= 0.005) return false;
  return true;
}

// The fits in words: the lags found, and what does not fit (a frame behind the window, one that
// looks like another frame). Frames of the second kind fail.
void describe_fits(const std::vector<LagFit>& fits, const LagGrid& grid, const std::vector<SavedFrame>& saved, Report& r) {
  double lo = 1e9, hi = -1e9;
  for (size_t k = 0; k < fits.size(); ++k) {
    const LagFit& f = fits[k];
    r.frames[k].lag_degrees = f.lag_degrees;
    if (k > 0) lo = std::min(lo, f.lag_degrees), hi = std::max(hi, f.lag_degrees);
    if (f.beyond_window)
      r.messages.push_back(saved[k].name + " was drawn " + degrees(grid.window) + " degrees or more behind " + degrees(grid.nominal(f.frame)) +
                           " (the window searched): compared at that limit");
    if (f.looks_like) {
      r.frames[k].grade.pass = false;
      if (r.diagnosis.empty()) r.diagnosis = to_string(Diagnosis::frames_out_of_order);
      r.messages.insert(r.messages.begin(), saved[k].name + " shows frame " + std::to_string(*f.looks_like) + "'s rotation (" +
                                                degrees(grid.nominal(*f.looks_like)) + " degrees), not frame " + std::to_string(k) +
                                                "'s (" + degrees(grid.nominal(f.frame)) + "): saved out of order, or twice?");
    }
  }
  if (without_lag(fits))
    r.messages.push_back("frames 1 to " + std::to_string(fits.size() - 1) + " were drawn at their nominal angles (no lag: a fixed clock)");
  else if (fits.size() > 1)
    r.messages.push_back("frames 1 to " + std::to_string(fits.size() - 1) + " were drawn " + degrees(lo) + " to " + degrees(hi) +
                         " degrees behind their nominal angles (the page draws with the previous frame's time), and were compared there");
}

// Where the frames came from (grade/provenance.h): ShadeLab's own render of the reference at the
// exact angles (the grid's lag-0 frames) loses the test where the course wants frames saved from
// its page, and is flagged where it does not; no lag on any frame otherwise is flagged for the TA.
void judge_provenance(Report& r, const std::vector<const image::Image*>& saved, const SharedFrames& grid_frames, const LagGrid& grid,
                      const std::vector<LagFit>& fits, bool frames_from_page) {
  std::vector<const image::Image*> exact;
  for (int k = 0; k < grid.frames; ++k) exact.push_back(grid_frames[grid.index(k, 0)].get());
  if (drawn_by_shadelab(saved, exact)) {
    r.flags.push_back(made_by_shadelab_flag(grid.frames));
    if (frames_from_page) {
      r.pass = false;
      r.score = 0;
      r.diagnosis = to_string(Diagnosis::made_by_shadelab);
      r.messages.insert(r.messages.begin(), save_from_the_page());
    }
  } else if (without_lag(fits)) {
    r.flags.push_back(no_lag_flag(grid.frames));
  }
}

// Pass when every frame passes (after the fits' findings). Saved frames score all or nothing; a
// code grade gives a share per passing frame (grader.cpp's assess).
void settle(Report& r) {
  r.pass = !r.frames.empty();
  for (const auto& f : r.frames) r.pass = r.pass && f.grade.pass;
  r.score = r.pass ? r.max_score : 0;
}

// The saved frames against the code's frames at the same angles: are they what the code renders?
Report code_match(const SharedFrames& saved, const SharedFrames& code, const SharedFrames& reference, const Report& frames_report,
                  const GradeSpec& spec, const GradeOptions& options) {
  Report r{spec.reference_name, false, 0, options.max_score, "", {}, {}, {}, {}};
  std::vector<int> differing;
  int code_matches_reference = 0;
  for (size_t k = 0; k < saved.size(); ++k) {
    GradeResult one = grade::grade({saved[k]}, {}, {code[k]}, {}, options);
    r.frames.push_back({one.frames[0], "homework", frames_report.frames[k].lag_degrees});
    if (!one.pass) differing.push_back(static_cast<int>(k));
    code_matches_reference += grade::grade({code[k]}, {}, {reference[k]}, {}, options).pass;
  }
  settle(r);
  if (differing.empty()) {
    r.messages.push_back("the saved frames are what your code renders, at the angles they were drawn at");
    return r;
  }
  const bool code_right = code_matches_reference == static_cast<int>(saved.size());
  const double outline = worst_outline_overlap(saved, code);
  if (outline < options.same_outline) {
    r.diagnosis = to_string(Diagnosis::frames_of_another_shape);
    r.messages.push_back("the saved frames show another shape than your code renders on this mesh (the outlines overlap by " + percent(outline) +
                         " at worst): saved with another mesh selected on the page?");
  } else if (differing.size() < saved.size()) {
    r.diagnosis = to_string(Diagnosis::edited_frames);
    r.messages.push_back("frame " + frame_list(differing) + (differing.size() == 1 ? " differs" : " differ") +
                         " from what your code renders, the others match: edited, or saved from another run?");
  } else if (code_right) {
    r.diagnosis = to_string(Diagnosis::stale_frames);
    r.messages.push_back("your code renders the reference, but the saved frames are not what it renders: saved from an earlier version of your code?" +
                         (frames_report.messages.empty() ? std::string() : " (the frames: " + frames_report.messages.front() + ")"));
  } else if (frames_report.pass) {
    r.diagnosis = to_string(Diagnosis::frames_not_from_code);
    r.messages.push_back("the saved frames match the reference, but your code renders something else: they were not made by this code");
  } else {
    r.diagnosis = to_string(Diagnosis::frames_not_from_code);
    r.messages.push_back("the saved frames are not what your code renders, and neither matches the reference");
  }
  return r;
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

// A failing set no mistake named, whose outline is not the reference's: another mesh.
void say_if_another_shape(Report& r, const SharedFrames& frames, const SharedFrames& reference, const GradeOptions& options) {
  const double outline = worst_outline_overlap(frames, reference);
  if (outline >= options.same_outline) return;
  r.diagnosis = to_string(Diagnosis::frames_of_another_shape);
  r.messages.insert(r.messages.begin(), "the saved frames show another shape than the reference on this mesh (the outlines overlap by " +
                                            percent(outline) + " at worst): saved with another mesh selected on the page?");
}

}  // namespace

std::optional<GradeSession::SavedFramesReading> GradeSession::saved_frames_explanation(const GradeSpec& spec, const GradeOptions& options,
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
  auto reference = at_angles(grid_request, mesh, at.angles);
  if (!reference) return std::nullopt;
  const auto* geometry = surfaces(*spec.formula, at, mesh, mesh_key, GeometryKept::in_memory);
  if (!geometry) return std::nullopt;
  FormulaRead read = explain_with_formula({&*spec.formula, at.uniforms, {}, geometry, &saved, &*reference,
                                           sampled_surfaces(*spec.formula, at, mesh, mesh_key, GeometryKept::in_memory),
                                           moved_flat_colour(*spec.formula, at, mesh)},
                                          options);
  // A page draws at or behind a frame's angle: an edge's move past it (frame 0's, by a few ten-
  // thousandths of a degree) is the placement's scatter.
  for (std::size_t k = 0; k < fits.size() && k < at.angles.size(); ++k)
    fits[k].lag_degrees = std::max(0.0, grid.nominal(fits[k].frame) - at.angles[k] - (k < read.angle_moves.size() ? read.angle_moves[k] : 0.0));
  return SavedFramesReading{std::move(read.explanation), std::move(fits)};
}

MovedFlatColour GradeSession::moved_flat_colour(const FormulaSpec& formula, const render::RenderRequest& at, const scene::Mesh& mesh) {
  auto requests = geometry_requests(formula, at);
  if (!requests) return {};
  const auto flat = std::find_if(requests->begin(), requests->end(), [](const GeometryRender& g) { return g.quantity == model::Quantity::flat_colour; });
  if (flat == requests->end()) return {};
  return [this, request = flat->request, &mesh](const std::vector<std::size_t>& angle, const std::vector<double>& offset) -> Expected<SharedFrames> {
    render::RenderRequest moved = request;
    moved.angles.clear();
    for (std::size_t i = 0; i < angle.size() && i < offset.size(); ++i)
      if (angle[i] < request.angles.size()) moved.angles.push_back(request.angles[angle[i]] + offset[i]);
    moved.frames = static_cast<int>(moved.angles.size());
    auto frames = frames_of(moved, mesh);
    if (frames) ++work_.rendered;
    return frames;
  };
}

Expected<SharedFrames> GradeSession::at_angles(render::RenderRequest request, const scene::Mesh& mesh, const std::vector<double>& angles) {
  request.angles = angles;
  request.frames = static_cast<int>(angles.size());
  request.pixel_type = image::PixelType::u8;
  auto frames = frames_of(request, mesh);
  if (frames) ++work_.rendered;
  return frames;
}

// Every mistake is rendered at the angles fitted against the reference; those that explain the
// frames best there (better than the reference, and within twice the best mistake's residual) are
// fitted on their own lag grid (frames of other shading fit the reference's grid at the wrong
// angles: the shading, not the rotation, decides the fit) and rendered again at their own angles.
// Most mistakes are ruled out by one render of the job.
GradeSession::MistakesAtLags GradeSession::mistakes_at_lags(const std::vector<const Mistake*>& which, const render::RenderRequest& grid_request,
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
    auto at = at_angles(mr, mesh, angles);
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
      if (auto own_grid = cached_frames(c.request, mesh, mesh_key)) {
        std::vector<LagFit> own = fit_lags(saved, *own_grid, grid);
        if (auto refit = at_angles(c.request, mesh, fitted_angles(own, grid))) {
          c.frames = std::move(*refit);
          out.fits.emplace_back(c.mistake->id, std::move(own));
        }
      }
    out.rendered.push_back({c.mistake->id, c.mistake->message, std::move(c.frames)});
  }
  return out;
}

Expected<FramesGradeOutput> GradeSession::grade_frames(const GradeSpec& spec, const render::RenderRequest& code, const std::vector<SavedFrame>& saved,
                                                       const MeshSource& mesh_source, const std::string& mesh_key, const EnterPhase& enter) {
  begin(spec);
  const auto failed = [&](const Error& e) { return FramesGradeOutput{failed_submission(e, spec.reference_name, spec.options.max_score), {}, {}}; };
  // The student's code first, under the compile deadline; its failure is the code's report.
  const bool has_code = !code.vertex.text.empty() || !code.fragment.text.empty();
  std::optional<Error> code_error;
  if (has_code)
    if (auto compiled = renderer_.compile(code.vertex, code.fragment); !compiled) code_error = compiled.error();
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
  auto grid_frames = cached_frames(ref, **mesh, mesh_key);
  if (!grid_frames) return make_error(ErrorCode::invalid_argument, "the reference does not render: " + grid_frames.error().message);
  std::vector<const image::Image*> saved_images;
  for (const auto& f : *frames) saved_images.push_back(f.get());
  const std::vector<LagFit> fits = fit_lags(saved_images, *grid_frames, grid);
  const std::vector<double> angles = fitted_angles(fits, grid);
  auto reference = at_angles(ref, **mesh, angles);
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
      if (auto read = saved_frames_explanation(spec, options, ref, **mesh, mesh_key, *frames, *grid_frames, grid)) {
        if (read->explanation.explained) diagnosed_fits = std::move(read->fits);
        explanation = std::move(read->explanation);
      }
    const CatalogueWork catalogue = catalogue_work(spec.mistakes, explanation);
    const auto recognised = recognised_mistake(catalogue);
    MistakesAtLags mistakes = mistakes_at_lags(catalogue.to_render, ref, **mesh, mesh_key, saved_images, fits, grid);
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
    auto rendered = frames_of(at, **mesh);
    if (auto s = enter(JobPhase::grader); !s) return s.take_error();
    out.code = rendered ? code_match(*frames, *rendered, *reference, out.frames, spec, options)
                        : failed_submission(rendered.error(), spec.reference_name, spec.options.max_score);
  }
  out.frames.grader_work = work_;
  if (spec.wants_heatmap(out.frames.pass)) out.heatmap_png = heatmap_png(*frames, *reference, code);
  return out;
}

}  // namespace shadelab::grade
