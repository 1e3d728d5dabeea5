#include "scene/mesh.h"

#include <algorithm>
#include <limits>

#include <glm/common.hpp>

#include "core/hash.h"

namespace shadelab::scene {

std::vector<float> Mesh::interleaved() const {
  std::vector<float> out;
  out.reserve(positions.size() * 6);
  for (size_t i = 0; i < positions.size(); ++i) {
    const auto& p = positions[i];
    const auto& n = normals[i];
    out.insert(out.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
  }
  return out;
}

std::string content_address(const Mesh& mesh) {
  const auto bytes = [](const std::vector<glm::vec3>& v) {
    return std::string_view(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(glm::vec3));
  };
  return sha256_hex(bytes(mesh.positions)) + sha256_hex(bytes(mesh.normals));
}

Bounds bounds(const Mesh& mesh) {
  if (mesh.positions.empty()) return {};
  Bounds b{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest())};
  for (const auto& p : mesh.positions) {
    b.min = glm::min(b.min, p);
    b.max = glm::max(b.max, p);
  }
  return b;
}

void fit_to(Mesh& mesh, const Bounds& target) {
  const Bounds b = bounds(mesh);
  const float height = b.max.y - b.min.y;
  // A flat mesh (height 0) keeps its size: there is no height to fit.
  const float scale = height > 0.f ? (target.max.y - target.min.y) / height : 1.f;
  const glm::vec3 anchor{(b.min.x + b.max.x) / 2, b.min.y, (b.min.z + b.max.z) / 2};
  const glm::vec3 place{(target.min.x + target.max.x) / 2, target.min.y, (target.min.z + target.max.z) / 2};
  for (auto& p : mesh.positions) p = (p - anchor) * scale + place;
}

}  // namespace shadelab::scene
