#include <glm/geometric.hpp>
#include <unordered_map>

#include "scene/mesh.h"

namespace shadelab::scene {

namespace {
struct PositionHash {
  size_t operator()(const glm::vec3& p) const {
    const auto h = [](float f) { return std::hash<float>{}(f == 0.f ? 0.f : f); };  // -0 == +0
    return h(p.x) * 73856093u ^ h(p.y) * 19349663u ^ h(p.z) * 83492791u;
  }
};

struct Accumulated {
  glm::dvec3 sum{0.0};
  glm::vec3 first_face{0.f};
  bool has_face = false;
};
}  // namespace

void compute_smooth_normals(Mesh& mesh) {
  std::unordered_map<glm::vec3, Accumulated, PositionHash> by_position;
  by_position.reserve(mesh.positions.size());
  for (size_t t = 0; t + 2 < mesh.positions.size(); t += 3) {
    const glm::dvec3 a = mesh.positions[t], b = mesh.positions[t + 1], c = mesh.positions[t + 2];
    // |(b - a) x (c - a)| is twice the area: summing unnormalised cross products weights by area.
    const glm::dvec3 face = glm::cross(b - a, c - a);
    const double length = glm::length(face);
    for (size_t k = 0; k < 3; ++k) {
      auto& acc = by_position[mesh.positions[t + k]];
      acc.sum += face;
      if (!acc.has_face && length > 0.0) {
        acc.first_face = glm::vec3(face / length);
        acc.has_face = true;
      }
    }
  }
  mesh.normals.resize(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const auto& acc = by_position[mesh.positions[i]];
    const double length = glm::length(acc.sum);
    mesh.normals[i] = length > 0.0 ? glm::vec3(acc.sum / length) : acc.first_face;
  }
  mesh.normals_from_file = false;
}

}  // namespace shadelab::scene
