#pragma once
// Frames a student saved from their browser (PNG files, in order), graded against the reference
// at the lag each was drawn with (grade/lag_fit.h) and, when the job carries their shaders,
// against what that code renders at the same angles.
#include <optional>
#include <string>
#include <vector>

#include "core/expected.h"
#include "grade/grade_renders.h"
#include "grade/grade_spec.h"
#include "grade/report.h"
#include "render/render_request.h"

namespace shadelab::grade {

struct FramesGradeOutput {
  Report frames;              // the saved frames against the reference
  std::optional<Report> code; // the saved frames against what the submission's code renders
  std::string heatmap_png;    // the saved frames against the reference at their lags
};

// `code` carries the course's job (canvas, frames, page) with or without shaders. What the
// submission causes is in the reports; an Error is the grader's own problem, as for judge_code.
Expected<FramesGradeOutput> judge_saved_frames(GradeRenders& renders, const GradeSpec& spec, const render::RenderRequest& code,
                                               const std::vector<SavedFrame>& saved, const MeshSource& mesh, const std::string& mesh_key,
                                               const EnterPhase& enter);

}  // namespace shadelab::grade
