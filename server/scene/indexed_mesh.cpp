#include "scene/indexed_mesh.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace shadelab::scene {

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

Status check_vertices(const IndexedMesh& m) {
  for (size_t v = 0; v < m.positions.size(); ++v)
    if (!finite(m.positions[v]))
      return make_error(ErrorCode::mesh_invalid,
                        "vertex " + std::to_string(v + 1) + " of mesh '" + m.name + "' has a NaN or infinite coordinate");
  for (size_t v = 0; v < m.normals.size(); ++v)
    if (!finite(m.normals[v]))
      return make_error(ErrorCode::mesh_invalid, "normal " + std::to_string(v + 1) + " of mesh '" + m.name + "' is NaN or infinite");
  return Ok{};
}

// In double: a float normal like (1e-20, 1e-20, 0) squares to a denormal in float, and the length
// that comes back is too inexact to make it unit (the fuzzer's STL, regressions/mesh_loader/crash-37c06ab9…).
glm::vec3 unit_or_zero(const glm::vec3& n) {
  const glm::dvec3 d(n);
  const double length = glm::length(d);
  return length > 0.0 && std::isfinite(length) ? glm::vec3(d / length) : glm::vec3(0.f);
}

}  // namespace

Status append_triangles(const IndexedMesh& source, const MeshLimits& limits, Mesh& mesh) {
  if (auto checked = check_vertices(source); !checked) return checked;
  std::uint64_t corner_count = 0;
  for (const std::uint32_t size : source.face_sizes) corner_count += size;
  if (corner_count != source.corners.size() || (!source.normals.empty() && source.normals.size() != source.positions.size()))
    return make_error(ErrorCode::mesh_invalid, "mesh '" + source.name + "' is inconsistent: its faces and vertices do not add up");
  const bool has_normals = !source.normals.empty();
  mesh.skipped_primitives += source.other_primitives;
  size_t first = 0;
  for (size_t f = 0; f < source.face_sizes.size(); first += source.face_sizes[f], ++f) {
    const std::uint32_t size = source.face_sizes[f];
    if (size < 3) {
      ++mesh.skipped_primitives;
      continue;
    }
    for (size_t k = first; k < first + size; ++k)
      if (source.corners[k] >= source.positions.size())
        return make_error(ErrorCode::mesh_invalid, "face " + std::to_string(f + 1) + " refers to vertex " +
                                                       std::to_string(std::uint64_t{source.corners[k]} + 1) + " of " +
                                                       std::to_string(source.positions.size()));
    for (size_t k = first + 1; k + 1 < first + size; ++k) {
      if (mesh.triangle_count() >= limits.max_triangles)
        return make_error(ErrorCode::mesh_too_large, "more than " + std::to_string(limits.max_triangles) + " triangles");
      for (const std::uint32_t idx : {source.corners[first], source.corners[k], source.corners[k + 1]}) {
        mesh.positions.push_back(source.positions[idx]);
        mesh.normals.push_back(has_normals ? unit_or_zero(source.normals[idx]) : glm::vec3(0.f));
      }
    }
  }
  return Ok{};
}

}  // namespace shadelab::scene
