// scene::load_mesh as a worker calls it on an uploaded file (ShadeLab reading OBJ and PLY, assimp STL, glTF
// and GLB, from memory, with the service's triangle limit). The selector byte picks the format the
// upload's name would give. Invariants on every mesh it accepts: whole triangles, finite
// positions within the limit, and normals of unit length (from the file, or computed), or zero
// only where a corner touches nothing but zero-area faces.
#include <cmath>
#include <span>
#include <string>

#include <glm/geometric.hpp>

#include "fuzz_check.h"
#include "scene/mesh.h"

namespace {
constexpr const char* kFormats[] = {"obj", "ply", "stl", "gltf", "glb"};

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool zero_area(const shadelab::scene::Mesh& mesh, size_t triangle) {
  const glm::dvec3 a = mesh.positions[3 * triangle], b = mesh.positions[3 * triangle + 1], c = mesh.positions[3 * triangle + 2];
  return glm::length(glm::cross(b - a, c - a)) == 0.0;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  shadelab::fuzz::InputReader input(data, size);
  const std::string format = kFormats[input.byte() % std::size(kFormats)];
  const std::string_view bytes = input.rest();
  // The fuzzer's inputs are small; a smaller limit reaches the limit's branch as well.
  const shadelab::scene::MeshLimits limits{.max_triangles = 4096};
  auto mesh = shadelab::scene::load_mesh({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()}, format,
                                         "upload." + format, limits);
  if (!mesh) {
    FUZZ_CHECK(!mesh.error().message.empty());
    return 0;
  }
  FUZZ_CHECK(!mesh->positions.empty() && mesh->positions.size() % 3 == 0);
  FUZZ_CHECK(mesh->triangle_count() <= limits.max_triangles);
  FUZZ_CHECK(mesh->normals.size() == mesh->positions.size());
  for (const auto& p : mesh->positions) FUZZ_CHECK(finite(p));
  for (size_t i = 0; i < mesh->normals.size(); ++i) {
    const glm::vec3 n = mesh->normals[i];
    FUZZ_CHECK(finite(n));
    const float length = glm::length(n);
    FUZZ_CHECK(length == 0.f || std::abs(length - 1.f) < 1e-3f);
    if (length == 0.f) FUZZ_CHECK(zero_area(*mesh, i / 3));
  }
  return 0;
}
