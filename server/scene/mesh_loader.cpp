#include <assimp/BaseImporter.h>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "core/embedded_files.h"
#include "scene/gltf_preflight.h"
#include "scene/indexed_mesh.h"
#include "scene/mesh.h"
#include "scene/obj_reader.h"
#include "scene/ply_reader.h"

namespace shadelab::scene {

namespace {

glm::mat4 to_glm(const aiMatrix4x4& m) {
  // assimp is row-major; glm is column-major.
  return glm::mat4(m.a1, m.b1, m.c1, m.d1, m.a2, m.b2, m.c2, m.d2, m.a3, m.b3, m.c3, m.d3, m.a4, m.b4, m.c4, m.d4);
}

// The formats an upload may be, each read by one reader. assimp reads some 40 formats, many
// rarely exercised; only the documented ones reach it.
constexpr std::string_view kFormats[] = {"obj", "ply", "stl", "gltf", "glb"};

bool supported(std::string_view format) { return std::find(std::begin(kFormats), std::end(kFormats), format) != std::end(kFormats); }

bool finite(const aiVector3D& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// One of assimp's meshes with its node's transform applied, as the file's faces index it.
IndexedMesh indexed(const aiMesh& m, const glm::mat4& world, const glm::mat3& normal_matrix) {
  IndexedMesh out;
  out.name = m.mName.C_Str();
  out.positions.reserve(m.mNumVertices);
  for (unsigned v = 0; v < m.mNumVertices; ++v) {
    const aiVector3D& p = m.mVertices[v];
    // A non-finite coordinate stays non-finite, for append_triangles to name its vertex.
    out.positions.push_back(finite(p) ? glm::vec3(world * glm::vec4(p.x, p.y, p.z, 1.f)) : glm::vec3(p.x, p.y, p.z));
  }
  if (m.HasNormals())
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      const aiVector3D& n = m.mNormals[v];
      out.normals.push_back(finite(n) ? normal_matrix * glm::vec3(n.x, n.y, n.z) : glm::vec3(n.x, n.y, n.z));
    }
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    const aiFace& face = m.mFaces[f];
    out.corners.insert(out.corners.end(), face.mIndices, face.mIndices + face.mNumIndices);
    out.face_sizes.push_back(face.mNumIndices);
  }
  return out;
}

struct Collector {
  const aiScene& scene;
  const MeshLimits& limits;
  Mesh& mesh;
  bool all_have_normals = true;

  Status collect(const aiNode& node, const glm::mat4& parent) {
    const glm::mat4 world = parent * to_glm(node.mTransformation);
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(world)));
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      const aiMesh& m = *scene.mMeshes[node.mMeshes[i]];
      all_have_normals = all_have_normals && m.HasNormals();
      if (auto s = append_triangles(indexed(m, world, normal_matrix), limits, mesh); !s) return s;
    }
    for (unsigned i = 0; i < node.mNumChildren; ++i)
      if (auto s = collect(*node.mChildren[i], world); !s) return s;
    return Ok{};
  }
};

// The file system an uploaded mesh sees: none. A glTF buffer's "uri" or an OBJ's "mtllib" is a
// path assimp opens; "uri": "/etc/passwd" rendered that file's bytes as vertices and reported
// their bounds. An upload is one file: its buffers are embedded (GLB, data: URIs).
class NoFileSystem final : public Assimp::IOSystem {
 public:
  bool Exists(const char*) const override { return false; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char*, const char*) override { return nullptr; }
  void Close(Assimp::IOStream*) override {}
};

// An assimp importer that holds only the readers of one format. assimp picks its reader by the
// file's extension, but when that reader declines the bytes it tries all its others by content:
// a PLY file named .glb reached assimp's PLY reader, and its crash, that way. So each format has
// an importer of its own, and the name says which reader a file meets.
class FormatImporter {
 public:
  explicit FormatImporter(std::string_view format) {
    importer_.SetIOHandler(new NoFileSystem);  // the importer owns it
    for (size_t i = importer_.GetImporterCount(); i-- > 0;) {
      const aiImporterDesc* desc = importer_.GetImporterInfo(i);
      if (desc && lists(desc->mFileExtensions, format)) continue;
      // UnregisterLoader hands the reader back to the caller, who deletes it.
      removed_.emplace_back(importer_.GetImporter(i));
      importer_.UnregisterLoader(removed_.back().get());
    }
  }
  Assimp::Importer& importer() { return importer_; }

 private:
  static bool lists(std::string_view extensions, std::string_view format) {
    for (size_t at = 0; at < extensions.size();) {
      const size_t end = std::min(extensions.find(' ', at), extensions.size());
      if (extensions.substr(at, end - at) == format) return true;
      at = end + 1;
    }
    return false;
  }
  Assimp::Importer importer_;
  std::vector<std::unique_ptr<Assimp::BaseImporter>> removed_;
};

// Reads STL, glTF and GLB; `all_have_normals` says whether the file gave every corner one.
Status read_with_assimp(std::span<const std::uint8_t> bytes, const std::string& format, const std::string& name,
                        const MeshLimits& limits, Mesh& mesh, bool& all_have_normals) {
  // Kept per thread and format: constructing an importer registers assimp's ~40 readers and its
  // post-processing steps, most of the time a small file takes to read.
  thread_local std::map<std::string, FormatImporter, std::less<>> importers;
  auto it = importers.find(format);
  if (it == importers.end()) it = importers.try_emplace(format, format).first;
  Assimp::Importer& importer = it->second.importer();
  // No step that reorders or welds vertices runs, so faces keep the file's order; polygons are
  // triangulated by append_triangles, not by aiProcess_Triangulate, whose assertions abort the
  // process on some malformed files (tests/fuzz/regressions/mesh_loader). ValidateDataStructure
  // rejects out-of-range indices.
  const unsigned flags = aiProcess_ValidateDataStructure;
  const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), flags, format.c_str());
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    return make_error(ErrorCode::mesh_parse_failed, "could not read '" + name + "' as " + format + ": " + importer.GetErrorString());
  Collector collector{*scene, limits, mesh};
  auto collected = collector.collect(*scene->mRootNode, glm::mat4(1.f));
  all_have_normals = collector.all_have_normals;
  importer.FreeScene();  // the mesh is copied out; the kept importer keeps nothing of the file
  return collected;
}

// A file read by one of ShadeLab's own readers (OBJ, PLY), whose formats index like assimp's.
Status append_file(Expected<IndexedMesh> file, const MeshLimits& limits, Mesh& mesh, bool& all_have_normals) {
  if (!file) return file.error();
  all_have_normals = !file->normals.empty();
  return append_triangles(*file, limits, mesh);
}

Status read_any(std::span<const std::uint8_t> bytes, const std::string& format, const std::string& name,
                const MeshLimits& limits, Mesh& mesh, bool& all_have_normals) {
  const std::string_view text{reinterpret_cast<const char*>(bytes.data()), bytes.size()};
  if (format == "obj") return append_file(read_obj(text, name, limits), limits, mesh, all_have_normals);
  if (format == "ply") return append_file(read_ply(text, name), limits, mesh, all_have_normals);
  if (format == "gltf" || format == "glb")
    if (auto checked = check_gltf(text, format == "glb", name, limits); !checked) return checked;
  return read_with_assimp(bytes, format, name, limits, mesh, all_have_normals);
}

// A zero-length normal is not a normal (normalize() in any shader makes it NaN): those corners
// take the smooth normal computed from the geometry, the others keep the file's.
void fill_missing_normals(Mesh& mesh) {
  if (std::none_of(mesh.normals.begin(), mesh.normals.end(), [](const glm::vec3& n) { return n == glm::vec3(0.f); })) return;
  Mesh computed = mesh;
  compute_smooth_normals(computed);
  for (size_t i = 0; i < mesh.normals.size(); ++i)
    if (mesh.normals[i] == glm::vec3(0.f)) mesh.normals[i] = computed.normals[i];
}

}  // namespace

Expected<Mesh> load_mesh(std::span<const std::uint8_t> bytes, const std::string& format_hint, const std::string& name,
                         const MeshLimits& limits) {
  if (bytes.empty()) return make_error(ErrorCode::mesh_empty, "the mesh file '" + name + "' is empty");
  if (!supported(format_hint))
    return make_error(ErrorCode::mesh_parse_failed, "'" + name + "' is a ." + format_hint +
                                                        " file; meshes are read from OBJ, PLY, STL, glTF and GLB files");
  Mesh mesh;
  mesh.name = name;
  bool all_have_normals = false;
  auto read = read_any(bytes, format_hint, name, limits, mesh, all_have_normals);
  if (!read) {
    Error e = read.error();
    if (e.code != ErrorCode::mesh_parse_failed) e.message = "'" + name + "': " + e.message;
    return e;
  }
  if (mesh.positions.empty()) return make_error(ErrorCode::mesh_empty, "'" + name + "' has no triangles to draw");
  for (const auto& p : mesh.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return make_error(ErrorCode::mesh_invalid, "'" + name + "': its node transforms move a vertex to infinity");
  if (!all_have_normals) {
    compute_smooth_normals(mesh);
    return mesh;
  }
  mesh.normals_from_file = true;
  fill_missing_normals(mesh);
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

Expected<Mesh> embedded_mesh(const std::string& path, const std::string& name) {
  const auto bytes = embedded_file(path);
  if (!bytes) return make_error(ErrorCode::mesh_not_found, "the mesh '" + name + "' (" + path + ") is not compiled into this binary");
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes->data());
  return load_mesh({data, bytes->size()}, mesh_format_of(path), name);
}

}  // namespace shadelab::scene
