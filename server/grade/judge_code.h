#pragma once
// A submission's code graded on a renderer: the orchestration between the worker's dispatch and
// the pure verdict in grader.h. The submission is rendered under the homework's light and each of
// the checkpoint's probe lights to 8-bit frames (what the canvas saves), with IEEE arithmetic and
// a census of the NaN and infinities the canvas cannot show; the reference is rendered the same
// way with the submission's uniform values, and grade() decides. Only a failing submission is
// explained: by the formula (grade/formula_explanation.h) where it can read the frames, and by the
// catalogue's mistakes it does not read, each rendered the same way.
#include <optional>
#include <string>

#include "core/expected.h"
#include "grade/grade_renders.h"
#include "grade/grade_spec.h"
#include "grade/report.h"
#include "grade/value_reading.h"
#include "render/render_request.h"

namespace shadelab::grade {

struct GradeOutput {
  Report report;
  std::string heatmap_png;  // the homework light's frames against the reference; empty when none rendered
  std::optional<repair::ValueAgreement> values;  // where the spec asks and the grade fails (GradeSpec::read_values)
};

// What the submission causes (it does not compile, renders NaN, ...) is in the report; an Error is
// the grader's own problem (the reference does not render, the mesh does not load). `mesh_key`
// names the mesh for the reference cache (the same key must mean the same mesh).
Expected<GradeOutput> judge_code(GradeRenders& renders, const GradeSpec& spec, const render::RenderRequest& submission,
                                 const MeshSource& mesh, const std::string& mesh_key, const EnterPhase& enter);

}  // namespace shadelab::grade
