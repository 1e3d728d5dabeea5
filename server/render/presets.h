#pragma once
// The reference shaders in shaders/, as JS-module pairs like the students' files.
#include <optional>
#include <string>
#include <vector>

#include "shader/shader_source.h"

namespace shadelab::render {

struct Preset {
  std::string name;         // "specular"
  std::string description;
  shader::ShaderFile vertex;    // name "specular_vert.js"
  shader::ShaderFile fragment;
};

const std::vector<Preset>& presets();  // starter, smooth, gouraud, diffuse, specular
std::optional<Preset> find_preset(const std::string& name);

}  // namespace shadelab::render
