#pragma once
// The renders a grade needs and where they are kept: the submission under every light the grade
// uses, the reference's and the known mistakes' frames through the worker's memory and the store
// (on disk and, in a cluster, the shared store), the formula's geometry, and frames at a saved
// set's own angles. Each grade begins here (its counts zeroed, the store its spec names opened);
// judge_code.h and judge_saved_frames.h decide from what it draws.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/expected.h"
#include "core/job_phase.h"
#include "core/lru_cache.h"
#include "grade/edge_placement.h"
#include "grade/formula_geometry.h"
#include "grade/grade_spec.h"
#include "grade/reference_cache.h"
#include "grade/reference_store.h"
#include "grade/report.h"
#include "model/surface.h"
#include "render/renderer.h"

namespace shadelab::grade {

// The job's mesh, loaded once the submission has compiled.
using MeshSource = std::function<Expected<const scene::Mesh*>()>;

// Where a grade's work changes hands, for the worker to tell its pool (core/job_phase.h):
// render once the submission has compiled (from then a hang or a crash is its render's), grader
// while the grader does its own work (the reference, the known mistakes, the comparisons: bounded
// separately and never charged to the submission).
using EnterPhase = std::function<Status(JobPhase phase)>;

// Where the formula's geometry is kept: with the references (the store too) for the course's own
// angles, which every code grade shares; in the worker's memory only for a student's saved
// frames' angles, which are theirs alone (108 MB of float frames a set at 512 x 512 on disk).
enum class GeometryKept { with_references, in_memory };

// The grid of where the first `job.frames` of `frames` differ from `reference`'s, as a PNG, drawn
// as `spec.picture` says (per pixel for staff, by blocks or not at all for a course's students);
// empty where it shows none or does not encode.
std::string heatmap_png(const SharedFrames& frames, const SharedFrames& reference, const render::RenderRequest& job, const GradeSpec& spec);

class GradeRenders {
 public:
  explicit GradeRenders(render::Renderer& renderer) : renderer_(renderer) {}

  // A grade's start: the counts zeroed, the store its spec names opened.
  void begin(const GradeSpec& spec);
  // What this grade's renders cost: rendered, from the store, from memory.
  const Report::GraderWork& work() const { return work_; }
  std::size_t reference_cache_bytes() const { return references_.bytes(); }
  render::Renderer& renderer() { return renderer_; }

  // `request` drawn, as it is: not the grader's work (the student's code) and not kept.
  Expected<SharedFrames> frames_of(const render::RenderRequest& request, const scene::Mesh& mesh);
  // `request` rendered at `angles` (the grader's work, counted).
  Expected<SharedFrames> at_angles(render::RenderRequest request, const scene::Mesh& mesh, const std::vector<double>& angles);
  // A reference set from the worker's memory, else from the store or rendered (and kept in both).
  Expected<SharedFrames> cached_frames(const render::RenderRequest& request, const scene::Mesh& mesh, const std::string& mesh_key);
  // A reference's or a mistake's frames, under the homework's light and then each probe light,
  // light by light through the caches.
  Expected<SharedFrames> cached_under_lights(const GradeSpec& spec, const render::RenderRequest& base, const scene::Mesh& mesh,
                                             const std::string& mesh_key);
  struct SubmissionFrames {
    SharedFrames frames;                       // every light's, in order
    std::vector<image::NonFinite> non_finite;  // each frame's, in the same order
  };
  // The submission under every light, drawn together, with the census of its colours.
  Expected<SubmissionFrames> submission_under_lights(const GradeSpec& spec, const render::RenderRequest& base, const scene::Mesh& mesh);
  // `base` under the homework's light, then under each probe light.
  Expected<std::vector<render::RenderRequest>> under_lights(const GradeSpec& spec, const render::RenderRequest& base);
  // `which` of the known mistakes, under every light, for a submission that failed.
  std::vector<RenderedMistake> rendered_mistakes(const GradeSpec& spec, const std::vector<const Mistake*>& which,
                                                 const render::RenderRequest& reference, const scene::Mesh& mesh, const std::string& mesh_key);

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

 private:
  // A set of frames from the store on disk (when the spec names one), else rendered (and kept
  // there); `work_` counts which.
  Expected<SharedFrames> stored_or_rendered(const render::RenderRequest& request, const scene::Mesh& mesh, const std::string& mesh_key);
  const std::string& mesh_address(const std::string& mesh_key, const scene::Mesh& mesh);
  // The cluster's store, connected once and kept for the next grade; null for none.
  store::SharedStore* shared_store(const store::SharedStoreConfig& config);
  Expected<render::RenderRequest> with_light(const GradeSpec& spec, const render::RenderRequest& base, const Probe& probe);

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
