#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "core/embedded_files.h"
#include "scene/mesh.h"

namespace shadelab::scene {

namespace {

glm::mat4 to_glm(const aiMatrix4x4& m) {
  // assimp is row-major; glm is column-major.
  return glm::mat4(m.a1, m.b1, m.c1, m.d1, m.a2, m.b2, m.c2, m.d2, m.a3, m.b3, m.c3, m.d3, m.a4, m.b4, m.c4, m.d4);
}

bool finite(const aiVector3D& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

struct Collector {
  const aiScene& scene;
  const MeshLimits& limits;
  Mesh& mesh;
  bool all_have_normals = true;
  std::string problem;  // first invalid datum, if any

  void collect(const aiNode& node, const glm::mat4& parent) {
    const glm::mat4 world = parent * to_glm(node.mTransformation);
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(world)));
    for (unsigned i = 0; i < node.mNumMeshes && problem.empty(); ++i)
      add(*scene.mMeshes[node.mMeshes[i]], world, normal_matrix);
    for (unsigned i = 0; i < node.mNumChildren && problem.empty(); ++i) collect(*node.mChildren[i], world);
  }

  void add(const aiMesh& m, const glm::mat4& world, const glm::mat3& normal_matrix) {
    if (!m.HasNormals()) all_have_normals = false;
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      if (!finite(m.mVertices[v])) {
        problem = "vertex " + std::to_string(v + 1) + " of mesh '" + m.mName.C_Str() + "' has a NaN or infinite coordinate";
        return;
      }
      if (m.HasNormals() && !finite(m.mNormals[v])) {
        problem = "normal " + std::to_string(v + 1) + " of mesh '" + m.mName.C_Str() + "' is NaN or infinite";
        return;
      }
    }
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices < 3) {
        ++mesh.skipped_primitives;
        continue;
      }
      for (unsigned k = 0; k < face.mNumIndices; ++k)
        if (face.mIndices[k] >= m.mNumVertices) {
          problem = "face " + std::to_string(f + 1) + " refers to vertex " + std::to_string(face.mIndices[k] + 1) + " of " +
                    std::to_string(m.mNumVertices);
          return;
        }
      // A polygon is a fan around its first corner, in the file's corner order (as the homework
      // page's loader draws it).
      for (unsigned k = 1; k + 1 < face.mNumIndices; ++k) {
        if (mesh.triangle_count() >= limits.max_triangles) {
          problem = "too many triangles";
          return;
        }
        for (const unsigned idx : {face.mIndices[0], face.mIndices[k], face.mIndices[k + 1]}) corner(m, idx, world, normal_matrix);
      }
    }
  }

  void corner(const aiMesh& m, unsigned idx, const glm::mat4& world, const glm::mat3& normal_matrix) {
    const aiVector3D& p = m.mVertices[idx];
    mesh.positions.push_back(glm::vec3(world * glm::vec4(p.x, p.y, p.z, 1.f)));
    if (!m.HasNormals()) {
      mesh.normals.emplace_back(0.f);
      return;
    }
    const aiVector3D& n = m.mNormals[idx];
    const glm::vec3 transformed = normal_matrix * glm::vec3(n.x, n.y, n.z);
    const float length = glm::length(transformed);
    mesh.normals.push_back(length > 0.f && std::isfinite(length) ? transformed / length : glm::vec3(0.f));
  }
};

}  // namespace

Expected<Mesh> load_mesh(std::span<const std::uint8_t> bytes, const std::string& format_hint, const std::string& name,
                         const MeshLimits& limits) {
  if (bytes.empty()) return make_error(ErrorCode::mesh_empty, "the mesh file '" + name + "' is empty");
  Assimp::Importer importer;
  // No step that reorders or welds vertices runs, so faces keep the file's order; polygons are
  // triangulated here, not by aiProcess_Triangulate, whose assertions abort the process on some
  // malformed files (tests/fuzz/regressions/mesh_loader). ValidateDataStructure rejects
  // out-of-range indices.
  const unsigned flags = aiProcess_ValidateDataStructure;
  const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), flags, format_hint.c_str());
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    return make_error(ErrorCode::mesh_parse_failed,
                      "could not read '" + name + "' as " + format_hint + ": " + importer.GetErrorString());
  Mesh mesh;
  mesh.name = name;
  Collector collector{*scene, limits, mesh};
  collector.collect(*scene->mRootNode, glm::mat4(1.f));
  if (collector.problem == "too many triangles")
    return make_error(ErrorCode::mesh_too_large,
                      "'" + name + "' has more than " + std::to_string(limits.max_triangles) + " triangles");
  if (!collector.problem.empty()) return make_error(ErrorCode::mesh_invalid, "'" + name + "': " + collector.problem);
  if (mesh.positions.empty())
    return make_error(ErrorCode::mesh_empty, "'" + name + "' has no triangles to draw");
  for (const auto& p : mesh.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return make_error(ErrorCode::mesh_invalid, "'" + name + "': its node transforms move a vertex to infinity");
  if (!collector.all_have_normals) {
    compute_smooth_normals(mesh);
    return mesh;
  }
  mesh.normals_from_file = true;
  // A zero-length normal is not a normal (normalize() in any shader makes it NaN): those corners
  // take the smooth normal computed from the geometry, the others keep the file's.
  if (std::any_of(mesh.normals.begin(), mesh.normals.end(), [](const glm::vec3& n) { return n == glm::vec3(0.f); })) {
    Mesh computed = mesh;
    compute_smooth_normals(computed);
    for (size_t i = 0; i < mesh.normals.size(); ++i)
      if (mesh.normals[i] == glm::vec3(0.f)) mesh.normals[i] = computed.normals[i];
  }
  return mesh;
}

Expected<Mesh> load_mesh_file(const std::string& path, const MeshLimits& limits) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::mesh_not_found, "cannot open mesh file '" + path + "'");
  const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), {}};
  const size_t slash = path.find_last_of('/');
  return load_mesh(bytes, mesh_format_of(path), slash == std::string::npos ? path : path.substr(slash + 1), limits);
}

std::string mesh_format_of(std::string_view filename) {
  const size_t slash = filename.find_last_of('/');
  if (slash != std::string_view::npos) filename.remove_prefix(slash + 1);
  const size_t dot = filename.find_last_of('.');
  return dot == std::string_view::npos || dot + 1 == filename.size() ? "obj" : std::string(filename.substr(dot + 1));
}

std::vector<std::string> builtin_mesh_names() { return {"bunny", "teapot"}; }

Expected<Mesh> builtin_mesh(const std::string& name) {
  const auto bytes = embedded_file("assets/" + name + ".obj");
  if (!bytes)
    return make_error(ErrorCode::mesh_not_found, "there is no built-in mesh '" + name + "' (built-ins: bunny, teapot)");
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes->data());
  return load_mesh({data, bytes->size()}, "obj", name);
}

}  // namespace shadelab::scene
