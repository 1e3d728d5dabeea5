#pragma once
// A mesh as a file stores it: shared vertices and polygons that index them. Every reader
// (assimp's, ShadeLab's own PLY reader) produces these, and append_triangles() turns them into
// the non-indexed Mesh the renderer draws, with one set of checks for every format.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/expected.h"
#include "scene/mesh.h"

namespace shadelab::scene {

struct IndexedMesh {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;          // one per position, or empty (computed later)
  std::vector<std::uint32_t> corners;      // every face's vertex indices, face after face
  std::vector<std::uint32_t> face_sizes;   // corners per face; points and lines have fewer than 3
  int other_primitives = 0;                // points and lines a reader counted without storing them
};

// Appends `source`'s faces to `mesh`, each polygon a fan around its first corner in the file's
// corner order (as the homework page's loader draws it); points and lines are counted in
// mesh.skipped_primitives. Normals are normalised (a zero or non-finite one becomes zero, to be
// computed). Errors: mesh_invalid (a non-finite coordinate or normal, an index out of range),
// mesh_too_large (over limits.max_triangles in all).
Status append_triangles(const IndexedMesh& source, const MeshLimits& limits, Mesh& mesh);

}  // namespace shadelab::scene
