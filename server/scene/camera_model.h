#pragma once
// The scene camera in double precision: where it is, where it looks, and how a point in the
// scene lands on the image. Rendering uses camera-relative matrices built from these in double
// and only then rounded to float, so a scene far from the origin keeps its precision.
#include <optional>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "scene/scene_description.h"

namespace shadelab::scene {

struct CameraModel {
  glm::dmat4 world_from_camera{1.0};
  glm::dmat4 camera_from_world{1.0};  // the view matrix
  ImagePlane plane;
  Projection type = Projection::perspective;
  double clip_start = 0.1, clip_end = 100;
  int width = 1920, height = 1080;  // Blender's default output

  glm::dvec3 location() const { return glm::dvec3(world_from_camera[3]); }
  double horizontal_fov_degrees() const;  // 0 for orthographic
  double vertical_fov_degrees() const;

  // Pixel coordinates (x right, y down, (0,0) the top-left corner of the image) of a scene point,
  // or nothing when it is at or behind the camera plane (perspective).
  std::optional<glm::dvec2> project(const glm::dvec3& world) const;
};

CameraModel make_camera(const Camera& camera, int width, int height);

}  // namespace shadelab::scene
