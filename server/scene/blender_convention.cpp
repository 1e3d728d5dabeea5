#include "scene/blender_convention.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace shadelab::scene {

glm::dmat3 euler_xyz_degrees(const glm::dvec3& degrees) {
  const glm::dvec3 r = degrees * (std::numbers::pi / 180.0);
  const double cx = std::cos(r.x), sx = std::sin(r.x), cy = std::cos(r.y), sy = std::sin(r.y);
  const double cz = std::cos(r.z), sz = std::sin(r.z);
  // glm is column-major: each glm::dvec3 below is a column.
  const glm::dmat3 rx(1, 0, 0, 0, cx, sx, 0, -sx, cx);
  const glm::dmat3 ry(cy, 0, -sy, 0, 1, 0, sy, 0, cy);
  const glm::dmat3 rz(cz, sz, 0, -sz, cz, 0, 0, 0, 1);
  return rz * ry * rx;
}

glm::dmat3 look_at_rotation(const glm::dvec3& from, const glm::dvec3& target) {
  glm::dvec3 forward = target - from;
  const double length = glm::length(forward);
  if (!(length > 0)) return glm::dmat3(1.0);
  forward /= length;
  // Straight up or down: world +Z cannot be "up"; Blender then keeps +Y of the world.
  const glm::dvec3 up_hint = std::abs(forward.z) > 0.999999 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, up_hint));
  const glm::dvec3 up = glm::cross(right, forward);
  return glm::dmat3(right, up, -forward);
}

glm::dmat4 object_matrix(const glm::dvec3& location, const glm::dmat3& rotation, const glm::dvec3& scale) {
  glm::dmat4 m(1.0);
  for (int c = 0; c < 3; ++c) m[c] = glm::dvec4(rotation[c] * scale[c], 0.0);
  m[3] = glm::dvec4(location, 1.0);
  return m;
}

bool format_is_y_up(const std::string& extension) {
  std::string e = extension;
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e != "stl" && e != "ply";
}

namespace {
bool fit_horizontal(SensorFit fit, int width, int height) {
  return fit == SensorFit::horizontal || (fit == SensorFit::automatic && width >= height);
}
}  // namespace

ImagePlane perspective_plane(double lens_mm, double sensor_mm, SensorFit fit, int width, int height) {
  const double half = 0.5 * sensor_mm / lens_mm, aspect = static_cast<double>(width) / height;
  return fit_horizontal(fit, width, height) ? ImagePlane{half, half / aspect} : ImagePlane{half * aspect, half};
}

ImagePlane orthographic_plane(double ortho_scale, SensorFit fit, int width, int height) {
  const double half = 0.5 * ortho_scale, aspect = static_cast<double>(width) / height;
  return fit_horizontal(fit, width, height) ? ImagePlane{half, half / aspect} : ImagePlane{half * aspect, half};
}

}  // namespace shadelab::scene
