#include "render/homework_contract.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

namespace shadelab::render {

FrameTransforms homework_transforms(const PageCamera& camera, int width, int height, double degrees) {
  // Built in double and rounded once, so frame k is exactly k times the step, with no drift.
  const glm::dmat4 projection = glm::perspective(glm::radians(camera.fov_y_degrees),
                                                 static_cast<double>(width) / static_cast<double>(height), camera.near, camera.far);
  const glm::dmat4 rotation = glm::rotate(glm::dmat4(1.0), glm::radians(degrees), glm::dvec3(0.0, 1.0, 0.0));
  const glm::dmat4 translation = glm::translate(glm::dmat4(1.0), camera.mesh_translation);
  return {glm::mat4(projection), glm::mat4(translation * rotation), glm::mat4(rotation)};
}

namespace {
void replace_all(std::string& s, std::string_view from, std::string_view to) {
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
}
}  // namespace

std::string frame_file_name(std::string_view pattern, std::string_view prefix, std::string_view index, std::string_view extension) {
  std::string name(pattern);
  replace_all(name, "{prefix}", prefix);
  replace_all(name, "{k}", index);
  return name + "." + std::string(extension);
}

std::string frame_file_name(std::string_view pattern, std::string_view prefix, int k, std::string_view extension) {
  return frame_file_name(pattern, prefix, std::to_string(k), extension);
}

}  // namespace shadelab::render
