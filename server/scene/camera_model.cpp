#include "scene/camera_model.h"

#include <cmath>
#include <numbers>

#include <glm/matrix.hpp>

namespace shadelab::scene {

CameraModel make_camera(const Camera& camera, int width, int height) {
  CameraModel m;
  const glm::dmat3 rotation = camera.rotation_degrees ? euler_xyz_degrees(*camera.rotation_degrees)
                                                      : look_at_rotation(camera.location, camera.target);
  m.world_from_camera = object_matrix(camera.location, rotation, glm::dvec3(1.0));
  m.camera_from_world = glm::inverse(m.world_from_camera);
  m.type = camera.type;
  m.plane = camera.type == Projection::perspective
                ? perspective_plane(camera.lens_mm, camera.sensor_width_mm, camera.sensor_fit, width, height)
                : orthographic_plane(camera.ortho_scale, camera.sensor_fit, width, height);
  m.clip_start = camera.clip_start;
  m.clip_end = camera.clip_end;
  m.width = width;
  m.height = height;
  return m;
}

double CameraModel::horizontal_fov_degrees() const {
  return type == Projection::perspective ? 2 * std::atan(plane.half_width) * 180 / std::numbers::pi : 0;
}
double CameraModel::vertical_fov_degrees() const {
  return type == Projection::perspective ? 2 * std::atan(plane.half_height) * 180 / std::numbers::pi : 0;
}

std::optional<glm::dvec2> CameraModel::project(const glm::dvec3& world) const {
  const glm::dvec3 p(camera_from_world * glm::dvec4(world, 1.0));
  double x = p.x, y = p.y;
  if (type == Projection::perspective) {
    if (!(-p.z > 0)) return std::nullopt;
    x /= -p.z;
    y /= -p.z;
  }
  const double ndc_x = x / plane.half_width, ndc_y = y / plane.half_height;
  return glm::dvec2((ndc_x + 1) * 0.5 * width, (1 - ndc_y) * 0.5 * height);
}

}  // namespace shadelab::scene
