#include "reference/phong_raycast.h"

#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>

namespace shadelab::reference {

glm::dvec3 phong(const PhongSphere& s, const glm::dvec3& p, const glm::dvec3& n) {
  const glm::dvec3 l = glm::normalize(s.light - p);
  const double ndotl = glm::dot(n, l);
  glm::dvec3 c = s.ambient + s.diffuse * s.light_color * std::max(0.0, ndotl);
  if (ndotl > 0.0) {
    const glm::dvec3 v = glm::normalize(-p);
    const glm::dvec3 r = glm::reflect(-l, n);
    c += s.specular * s.light_color * std::pow(std::max(0.0, glm::dot(v, r)), s.specular_alpha);
  }
  return c;
}

image::Image raycast(const PhongSphere& s, int width, int height, int n) {
  image::Image out = image::Image::blank(width, height, image::PixelType::f32);
  // The page's camera: the eye at the origin looking down -Z; the mesh moved by the camera's
  // translation (its rotation about Y leaves a sphere on the axis unchanged).
  const glm::dvec3 center = s.center + s.camera.mesh_translation;
  const double tan_half = std::tan(s.camera.fov_y_degrees * M_PI / 360.0), aspect = static_cast<double>(width) / height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      glm::dvec3 sum(0.0);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          // Sample positions on a regular n x n grid inside the pixel; y up in NDC, rows top-down.
          const double px = (x + (i + 0.5) / n) / width * 2.0 - 1.0;
          const double py = 1.0 - (y + (j + 0.5) / n) / height * 2.0;
          const glm::dvec3 dir = glm::normalize(glm::dvec3(px * tan_half * aspect, py * tan_half, -1.0));
          // |t dir - c|^2 = r^2, with |dir| = 1.
          const double b = glm::dot(dir, center), disc = b * b - (glm::dot(center, center) - s.radius * s.radius);
          if (disc < 0.0) continue;  // background: black
          const double t = b - std::sqrt(disc);
          const glm::dvec3 p = t * dir;
          const glm::dvec3 c = phong(s, p, glm::normalize(p - center));
          sum += glm::clamp(c, 0.0, 1.0);
        }
      const glm::vec3 c(sum / double(n * n));
      const float px[4] = {c.r, c.g, c.b, 1.0f};
      std::memcpy(out.bytes.data() + (static_cast<size_t>(y) * width + x) * 16, px, sizeof px);
    }
  return out;
}

}  // namespace shadelab::reference
