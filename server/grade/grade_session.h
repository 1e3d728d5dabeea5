#pragma once
// Grading one submission on a renderer: the orchestration between the worker's dispatch and the
// pure verdict in grader.h. The submission is rendered under the homework's light and each of the
// checkpoint's probe lights to 8-bit frames (what the canvas saves), with IEEE arithmetic and a
// census of the NaN and infinities the canvas cannot show; the reference is rendered the same way
// with the submission's uniform values, and grade() decides. Only a failing submission is
// explained: by the formula (grade/formula_explanation.h) where it can read the frames, and by the
// catalogue's mistakes it does not read, each rendered the same way.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/expected.h"
#include "core/job_phase.h"
#include "grade/edge_placement.h"
#include "grade/formula_geometry.h"
#include "grade/grade_spec.h"
#include "grade/lag_fit.h"
#include "grade/reference_cache.h"
#include "grade/reference_store.h"
#include "grade/report.h"
#include "model/surface.h"
#include "core/lru_cache.h"
#include "render/renderer.h"

namespace shadelab::grade {

struct GradeOutput {
  Report report;
  std::string heatmap_png;  // the homework light's frames against the reference; empty when none rendered
};

// The job's mesh, loaded once the submission has compiled.
using MeshSource = std::function<Expected<const scene::Mesh*>()>;

// Where a grade's work changes hands, for the worker to tell its pool (core/job_phase.h):
// render once the submission has compiled (from then a hang or a crash is its render's), grader
// while the grader does its own work (the reference, the known mistakes, the comparisons: bounded
// separately and never charged to the submission).
using EnterPhase = std::function<Status(JobPhase phase)>;

struct FramesGradeOutput {
  Report frames;              // the saved frames against the reference
  std::optional<Report> code; // the saved frames against what the submission's code renders
  std::string heatmap_png;    // the saved frames against the reference at their lags
};

class GradeSession {
 public:
  explicit GradeSession(render::Renderer& renderer) : renderer_(renderer) {}

  // What the submission causes (it does not compile, renders NaN, ...) is in the report; an Error
  // is the grader's own problem (the reference does not render, the mesh does not load).
  // `mesh_key` names the mesh for the reference cache (the same key must mean the same mesh).
  Expected<GradeOutput> grade(const GradeSpec& spec, const render::RenderRequest& submission, const MeshSource& mesh,
                              const std::string& mesh_key, const EnterPhase& enter);

  // Frames a student saved from their browser (PNG files, in order), graded against the reference
  // at the lag each was drawn with (grade/lag_fit.h) and, when `code` holds their shaders, against
  // what that code renders at the same angles. `code` carries the course's job (canvas, frames,
  // page) with or without shaders. Errors as grade()'s.
  Expected<FramesGradeOutput> grade_frames(const GradeSpec& spec, const render::RenderRequest& code, const std::vector<SavedFrame>& saved,
                                           const MeshSource& mesh, const std::string& mesh_key, const EnterPhase& enter);

  std::size_t reference_cache_bytes() const { return references_.bytes(); }

 private:
  Expected<SharedFrames> frames_of(const render::RenderRequest& request, const scene::Mesh& mesh);
  // The grid of where the first `job.frames` of `frames` differ from `reference`'s, as a PNG (empty
  // if it does not encode).
  static std::string heatmap_png(const SharedFrames& frames, const SharedFrames& reference, const render::RenderRequest& job);
  // A set of frames from the store on disk (when the spec names one), else rendered (and kept
  // there); `work` counts which.
  Expected<SharedFrames> stored_or_rendered(const render::RenderRequest& request, const scene::Mesh& mesh, const std::string& mesh_key);
  // A reference set from the worker's memory, else stored_or_rendered (and kept in memory).
  Expected<SharedFrames> cached_frames(const render::RenderRequest& request, const scene::Mesh& mesh, const std::string& mesh_key);
  // Those of the known mistakes, under every light, for a submission that failed.
  std::vector<RenderedMistake> rendered_mistakes(const GradeSpec& spec, const std::vector<const Mistake*>& which,
                                                 const render::RenderRequest& reference, const scene::Mesh& mesh, const std::string& mesh_key);
  const std::string& mesh_address(const std::string& mesh_key, const scene::Mesh& mesh);
  // A grade's start: the counts zeroed, the store its spec names opened.
  void begin(const GradeSpec& spec);
  // The cluster's store, connected once and kept for the next grade; null for none.
  store::SharedStore* shared_store(const store::SharedStoreConfig& config);
  // `which` of the known mistakes (catalogue_work's), compared with a failing set of saved frames,
  // each at the angles the frames fit it at (`fits` says which mistake's, when not the reference's).
  struct MistakesAtLags {
    std::vector<RenderedMistake> rendered;
    std::vector<std::pair<std::string, std::vector<LagFit>>> fits;
  };
  MistakesAtLags mistakes_at_lags(const std::vector<const Mistake*>& which, const render::RenderRequest& grid_request,
                                  const scene::Mesh& mesh, const std::string& mesh_key, const std::vector<const image::Image*>& saved,
                                  const std::vector<LagFit>& fits, const LagGrid& grid);
  // `request` rendered at `angles` (the grader's work, counted).
  Expected<SharedFrames> at_angles(render::RenderRequest request, const scene::Mesh& mesh, const std::vector<double>& angles);
  // `base` under the homework's light, then under each probe light.
  Expected<std::vector<render::RenderRequest>> under_lights(const GradeSpec& spec, const render::RenderRequest& base);
  Expected<SharedFrames> cached_under_lights(const GradeSpec& spec, const render::RenderRequest& base, const scene::Mesh& mesh,
                                             const std::string& cache_key);
  struct SubmissionFrames {
    SharedFrames frames;                       // every light's, in order
    std::vector<image::NonFinite> non_finite;  // each frame's, in the same order
  };
  Expected<SubmissionFrames> submission_under_lights(const GradeSpec& spec, const render::RenderRequest& base, const scene::Mesh& mesh);
  Expected<render::RenderRequest> with_light(const GradeSpec& spec, const render::RenderRequest& base, const Probe& probe);
  // Where the formula's geometry is kept: with the references (the store too) for the course's own
  // angles, which every code grade shares; in the worker's memory only for a student's saved
  // frames' angles, which are theirs alone (108 MB of float frames a set at 512 x 512 on disk).
  enum class GeometryKept { with_references, in_memory };
  // The geometry the formula is evaluated on, per angle of `reference`: from the worker's memory,
  // else from the store or rendered (grade/formula_geometry.h); null when it does not render. Each
  // sample's flat normal is added to the averaged geometry's copy: four renders more, no reload.
  const std::vector<model::FrameSurface>* surfaces(const FormulaSpec& formula, const render::RenderRequest& reference,
                                                   const scene::Mesh& mesh, const std::string& mesh_key, GeometryKept kept,
                                                   SampleGeometry samples = SampleGeometry::averaged);
  // The evidence's way to the geometry with each sample's flat normal, where the formula has any.
  std::function<const std::vector<model::FrameSurface>*()> sampled_surfaces(const FormulaSpec& formula, const render::RenderRequest& reference,
                                                                           const scene::Mesh& mesh, const std::string& mesh_key, GeometryKept kept);
  // Saved frames' flat colour drawn again at moved angles (grade/edge_placement.h), where the
  // formula has one; each render counted as the grader's work.
  MovedFlatColour moved_flat_colour(const FormulaSpec& formula, const render::RenderRequest& at, const scene::Mesh& mesh);
  // A failing submission's frames read by the checkpoint's formula (grade/formula_explanation.h),
  // on the geometry of `reference` (rendered once per course, kept as references are); none when
  // the spec has no formula or the geometry does not render.
  std::optional<Explanation> formula_explanation(const GradeSpec& spec, const render::RenderRequest& reference, const scene::Mesh& mesh,
                                                 const std::string& mesh_key, const SharedFrames& student, const SharedFrames& reference_frames);
  // Failing saved frames read by the formula: on the geometry at the angles their outlines fit
  // (grade/lag_fit.h's fit_outline_lags: shading of another kind misleads the reference's fit),
  // against the reference rendered at the same angles, under the saved frames' `options`.
  struct SavedFramesReading {
    Explanation explanation;
    // The angles it read the frames at: their outlines' fit, moved where placed by their edges.
    std::vector<LagFit> fits;
  };
  std::optional<SavedFramesReading> saved_frames_explanation(const GradeSpec& spec, const GradeOptions& options, const render::RenderRequest& grid_request,
                                                      const scene::Mesh& mesh, const std::string& mesh_key, const SharedFrames& saved,
                                                      const SharedFrames& grid_frames, const LagGrid& grid);

  render::Renderer& renderer_;
  // Reference and mistake renders depend only on their shaders and the job's parameters: a batch
  // grading a class renders them once per worker, and with a store, once per course.
  ReferenceCache references_;
  // The formula's geometry, as the object's pixels: ~35 MB a set of 9 frames of the bunny at 512 x
  // 512 (~65 MB with each sample's flat normal): the course's two sets of its own angles, which a
  // class's code grades share.
  LruCache<std::vector<model::FrameSurface>> surfaces_{8, 112u << 20};
  std::optional<ReferenceStore> store_;   // the current grade's (its spec names the places)
  std::unique_ptr<store::SharedStore> shared_;
  store::SharedStoreConfig shared_config_;
  Report::GraderWork work_;               // the current grade's
  std::string address_of_, address_;      // the last mesh key's content address (the store's keys)
};

}  // namespace shadelab::grade
