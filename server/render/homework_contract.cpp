#include "render/homework_contract.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

namespace shadelab::render {

FrameTransforms homework_transforms(int width, int height, double degrees) {
  // Built in double and rounded once, so frame k is exactly 20 * k degrees, with no drift.
  const glm::dmat4 projection =
      glm::perspective(glm::radians(45.0), static_cast<double>(width) / static_cast<double>(height), 0.1, 100.0);
  const glm::dmat4 rotation = glm::rotate(glm::dmat4(1.0), glm::radians(degrees), glm::dvec3(0.0, 1.0, 0.0));
  const glm::dmat4 translation = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, -2.0, -7.5));
  return {glm::mat4(projection), glm::mat4(translation * rotation), glm::mat4(rotation)};
}

const std::vector<ConstantUniform>& homework_constant_uniforms() {
  // The values of hw2.js, under both names the handout allows.
  static const std::vector<ConstantUniform> table = {
      {"uAmbientColor", "vec4", {0.2f, 0.1f, 0.1f, 1.0f}, 4},
      {"uDiffuseColor", "vec4", {0.7f, 0.5f, 0.1f, 1.0f}, 4},
      {"uSpecularColor", "vec4", {0.1f, 0.4f, 0.8f, 1.0f}, 4},
      {"uLightPosition", "vec3", {16.0f, 8.0f, 4.0f, 0.0f}, 3},
      {"uLightColor", "vec4", {1.0f, 1.0f, 1.0f, 1.0f}, 4},
      {"ambientColor", "vec4", {0.2f, 0.1f, 0.1f, 1.0f}, 4},
      {"diffuseColor", "vec4", {0.7f, 0.5f, 0.1f, 1.0f}, 4},
      {"specularColor", "vec4", {0.1f, 0.4f, 0.8f, 1.0f}, 4},
      {"lightPosition", "vec3", {16.0f, 8.0f, 4.0f, 0.0f}, 3},
      {"lightColor", "vec4", {1.0f, 1.0f, 1.0f, 1.0f}, 4},
  };
  return table;
}

}  // namespace shadelab::render
