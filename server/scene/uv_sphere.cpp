#include "scene/uv_sphere.h"

#include <cmath>
#include <numbers>

namespace shadelab::scene {

Mesh uv_sphere(double radius, glm::dvec3 center, int segments) {
  Mesh m;
  m.name = "uv_sphere_" + std::to_string(segments);
  const int rings = std::max(2, segments / 2);
  const auto point = [&](int ring, int seg) {
    const double theta = std::numbers::pi * ring / rings, phi = 2 * std::numbers::pi * seg / segments;
    return glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
  };
  const auto add = [&](const glm::dvec3& n) {
    m.positions.push_back(glm::vec3(center + radius * n));
    m.normals.push_back(glm::vec3(n));
  };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const glm::dvec3 a = point(r, s), b = point(r + 1, s), c = point(r + 1, s + 1), d = point(r, s + 1);
      if (r > 0) add(a), add(b), add(d);            // the top ring's quads are single triangles
      if (r < rings - 1) add(d), add(b), add(c);    // and so are the bottom ring's
    }
  m.normals_from_file = true;
  return m;
}

}  // namespace shadelab::scene
