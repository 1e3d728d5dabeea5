#pragma once
// Which value each active uniform of a linked program gets, decided before anything is drawn:
// the page's constants (the course's values), overridden by the request's values, each type-checked against the
// program's reflection. A value for a uniform the program does not use is a warning.
#include <string>
#include <vector>

#include "core/expected.h"
#include "gl/program.h"
#include "render/homework_contract.h"

namespace shadelab::render {

struct UniformSetting {
  std::string name;            // GLSL name; "lights" or "lights[0]" for an array
  std::vector<double> values;  // components x elements, column-major for matrices
};

struct UniformAssignment {
  const gl::ActiveVariable* uniform;
  std::vector<float> values;
};

struct UniformPlan {
  std::vector<UniformAssignment> constant;  // uploaded once per program
  // Fed per frame from homework_transforms() unless the request set them.
  const gl::ActiveVariable* world_to_clip = nullptr;
  const gl::ActiveVariable* mesh_to_world = nullptr;
  const gl::ActiveVariable* mesh_to_world_rot = nullptr;
  std::vector<std::string> warnings;
};

// `active` must outlive the plan (it points into it). `page`: what the page sets every program.
Expected<UniformPlan> plan_uniforms(const std::vector<gl::ActiveVariable>& active, const std::vector<ConstantUniform>& page,
                                    const std::vector<UniformSetting>& settings);

}  // namespace shadelab::render
