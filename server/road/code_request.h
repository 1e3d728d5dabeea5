#pragma once
// A code grade as a client shapes it (POST /api/grade, the page): the student's shaders (or a
// preset the caller may see), what they are graded against (a checkpoint, or the page's own
// reference), and what the client may change in how they are drawn. The road alone turns it into
// the grade's job: every fact the request leaves out is the course's (canvas, frames, page setup,
// mesh, the checkpoint's tolerance and points), so an adapter parses fields and never asks the
// course for a spec.
#include <optional>
#include <string>
#include <vector>

#include "core/expected.h"
#include "course/access.h"
#include "course/course.h"
#include "render/render_request.h"
#include "road/submission.h"

namespace shadelab::road {

// How the code is drawn, where the client changes it; unset: the course's.
struct RenderShape {
  std::optional<int> width, height, frames, msaa;
  std::optional<double> degrees_per_frame;
  std::vector<render::UniformSetting> uniforms;  // over the page's values
  bool fit = false;                              // fitted into the course's default mesh's bounds
};

// One of the course's meshes by name (empty: its default), or a mesh the client uploaded.
struct MeshChoice {
  struct Upload {
    std::string id;      // its content address, the workers' cache key
    std::string format;  // file extension: obj, glb, ...
    std::string bytes;
  };
  std::string name;
  std::optional<Upload> upload;
};

// The tolerance a client may set; unset: the checkpoint's (or the course's, for its own reference).
struct ToleranceShape {
  std::optional<double> threshold, max_failing_fraction, max_score;
  bool spatial_tolerance = false;
};

struct CodeRequest {
  std::optional<ShaderPair> code;          // the student's shaders...
  std::string preset;                      // ...or a preset of the course, by name
  std::string reference;                   // a checkpoint (or an alias of one)...
  std::optional<ShaderPair> own_reference;  // ...or the page's own reference ("custom")
  RenderShape render;
  MeshChoice mesh;
  ToleranceShape tolerance;
};

// The submission and what the road noticed on the way (an alias's note).
struct BuiltCode {
  CodeSubmission submission;
  std::vector<std::string> warnings;
};

// The grade's job for `request`, drawn within `limits`. A preset must be one `viewer` may see; a
// checkpoint, a mesh or a size the course does not have is an Error. The sources are not checked
// here: grade_code checks them once, with the same limits.
Expected<BuiltCode> code_submission(const course::Course& course, CodeRequest request, const course::Viewer& viewer,
                                    const render::RenderLimits& limits);

}  // namespace shadelab::road
