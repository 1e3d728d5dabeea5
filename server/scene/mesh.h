#pragma once
// A triangle mesh as the homework page draws it: non-indexed, three corners per triangle in the
// file's face order (so `flat` varyings take each triangle's last corner, as in the browser).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/expected.h"

namespace shadelab::scene {

struct Mesh {
  std::string name;
  std::vector<glm::vec3> positions;  // 3 per triangle
  std::vector<glm::vec3> normals;    // same size as positions
  bool normals_from_file = false;
  int skipped_primitives = 0;        // points and lines in the file, which a triangle draw ignores

  size_t triangle_count() const { return positions.size() / 3; }
  // 6 floats per corner: position then normal, as gl::MeshBuffer takes them.
  std::vector<float> interleaved() const;
};

// What names a mesh's data in a cache: the SHA-256 of its positions and of its normals. One
// worker's caches serve every tenant, so the name must resist a crafted collision (core/hash.h).
// It is taken from the arrays as they are: ~40 ms for a million triangles on the 2-core machine,
// where building the interleaved array to FNV-hash it took ~115 ms.
std::string content_address(const Mesh& mesh);

// The memory a mesh's positions and normals take.
inline std::size_t bytes_of(const Mesh& mesh) { return (mesh.positions.size() + mesh.normals.size()) * sizeof(glm::vec3); }

struct Bounds {
  glm::vec3 min{0.f}, max{0.f};
};
Bounds bounds(const Mesh& mesh);

// Area-weighted smooth normals, summed per distinct position so that split vertices (UV seams,
// patch seams) do not crease. Degenerate faces add nothing; a position whose sum is zero takes
// the normal of its first non-degenerate face, or (0, 0, 0) if it only touches zero-area faces,
// which rasterise nothing. Never NaN.
void compute_smooth_normals(Mesh& mesh);

// Scales and moves `mesh` into the framing of `target` (a course's default mesh, which the page
// draws in its own units): the same height, its base at the target's lowest y, its bounding box
// centred on the target's in x and z. A flat mesh (height 0) keeps its size.
void fit_to(Mesh& mesh, const Bounds& target);

struct MeshLimits {
  size_t max_triangles = 2'000'000;
};

// Loads OBJ and PLY (ShadeLab's own readers), STL, glTF and GLB (assimp's), from memory. `format_hint` is
// the file extension ("obj", "glb", ...). Positions are used as the file has them (node transforms
// applied); normals from the file when it has them, else computed.
Expected<Mesh> load_mesh(std::span<const std::uint8_t> bytes, const std::string& format_hint,
                         const std::string& name, const MeshLimits& limits = {});
Expected<Mesh> load_mesh_file(const std::string& path, const MeshLimits& limits = {});
// The format hint of a file name or path: its extension ("glb"), or "obj" when it has none.
std::string mesh_format_of(std::string_view filename);

// A mesh file compiled into the binary ("assets/suzanne.obj"), named `name`.
Expected<Mesh> embedded_mesh(const std::string& path, const std::string& name);

}  // namespace shadelab::scene
