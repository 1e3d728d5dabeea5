#pragma once
// The student's fragment values against the reference's (repair/value_probes.h): each probe of
// both programs drawn into a float target on a small canvas (the repair screens' size and three
// angles), a pass per run of up to the driver's outputs (shader/uniform_variants.h), and compared
// at every pixel where both were drawn. What it finds goes to the repair search only: it says
// which of the student's values need no edit, never a verdict nor anything a student sees.
#include <vector>

#include "core/expected.h"
#include "render/renderer.h"
#include "repair/value_probes.h"

namespace shadelab::grade {

struct ValueCanvas {
  int size = 64;   // the longer side, in pixels
  int frames = 3;  // a third of a turn apart, as the repair's screens
};

// `student` and `reference` under each light to read the values at (the same lights, in the
// same order: the page's and those the student's frames fail under). Not read (`read` false)
// where either fragment stage cannot be probed or its probes do not draw.
repair::ValueAgreement read_values(render::Renderer& renderer, const std::vector<render::RenderRequest>& student,
                                   const std::vector<render::RenderRequest>& reference, const scene::Mesh& mesh,
                                   const ValueCanvas& canvas = {});

}  // namespace shadelab::grade
