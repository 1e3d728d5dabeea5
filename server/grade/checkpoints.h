#pragma once
// The homework's checkpoints as grading references, each with the mistakes students make on it.
// A mistake is the reference shader with one deliberate change; a submission that matches a
// mistake's render better than the reference's is told, in those words, what it got wrong.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/expected.h"
#include "grade/grader.h"
#include "shader/shader_source.h"

namespace shadelab::grade {

struct Mistake {
  std::string id;       // "missing_specular"
  std::string message;  // what the student reads
  shader::ShaderFile vertex, fragment;
};

// Extra frames rendered under another light, for mistakes the homework's light cannot show: with
// the light at (16, 8, 4) the unlit side barely faces the camera, so a specular term added where
// N.L <= 0 changes under 0.1% of the pixels. Behind the mesh, that side is in view.
struct Probe {
  std::string name;
  std::array<float, 3> light_position;
};

struct Checkpoint {
  std::string name;  // smooth, gouraud, diffuse, specular
  shader::ShaderFile vertex, fragment;
  std::vector<Mistake> mistakes;
  std::vector<Probe> probes;
};

std::optional<Checkpoint> find_checkpoint(const std::string& name);

// What a submission is compared against.
struct GradeSpec {
  std::string reference_name;  // a checkpoint, or "custom"
  shader::ShaderFile reference_vertex, reference_fragment;
  std::vector<Mistake> mistakes;
  std::vector<Probe> probes;
  GradeOptions options;
};

// The spec of one of the homework's checkpoints; unknown_preset for another name.
Expected<GradeSpec> checkpoint_spec(const std::string& checkpoint, const GradeOptions& options);

std::vector<std::string> checkpoint_names();

}  // namespace shadelab::grade
