#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "core/embedded_files.h"
#include "core/hash.h"
#include "course/course_reader.h"
#include "scene/mesh.h"

using namespace shadelab;

namespace {
Expected<scene::Mesh> load(const std::string& text, const std::string& format) {
  return scene::load_mesh({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}, format, "test." + format);
}
bool all_finite(const scene::Mesh& m) {
  for (const auto& n : m.normals)
    if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) return false;
  return true;
}
}  // namespace

// The course's two meshes as its HW2 folder hands them out (docs/homework-contract.md's table):
// the same bytes, every triangle with the file's own normals, drawn in the file's units.
TEST(MeshLoaderTest, TheCoursesMeshesAreTheFilesItHandsOutInTheirOwnUnits) {
  struct Expected {
    const char* name;
    const char* sha256;
    size_t triangles;
    glm::vec3 min, max;  // the contract's bounds, to two decimals
  };
  const Expected meshes[] = {
      {"bunny", "549a9a95a61bdd4ee4caeda28331d936f082122353ff16d6861cd41c4c64c4c6", 27779, {-2.02f, -0.01f, -1.61f}, {2.03f, 4.00f, 1.53f}},
      {"teapot", "41b957ba8282b79f9a1ab8ff52cc6534253bdab742dbaffc4b8360e36f39b3f1", 6192, {-2.31f, 0.01f, -1.55f}, {2.67f, 2.45f, 1.55f}}};
  for (const auto& e : meshes) {
    const course::CourseMesh* m = course::builtin_course().mesh(e.name);
    ASSERT_NE(m, nullptr) << e.name;
    EXPECT_TRUE(m->embedded);
    EXPECT_EQ(sha256_hex(std::string(*embedded_file(m->id))), e.sha256) << e.name;
    auto mesh = course::load_course_mesh(*m);
    ASSERT_TRUE(mesh) << mesh.error().format();
    EXPECT_TRUE(mesh->normals_from_file);
    EXPECT_EQ(mesh->triangle_count(), e.triangles);
    const auto b = scene::bounds(*mesh);
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_NEAR(b.min[axis], e.min[axis], 0.006) << e.name << " axis " << axis;
      EXPECT_NEAR(b.max[axis], e.max[axis], 0.006) << e.name << " axis " << axis;
    }
    for (const auto& n : mesh->normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-3);
  }
  EXPECT_EQ(scene::embedded_mesh("assets/dragon.obj", "dragon").error().code, ErrorCode::mesh_not_found);
}

TEST(MeshLoaderTest, FacesKeepTheFilesOrderAndCorners) {
  // The last corner of each triangle is what a `flat` varying takes; it must be the file's.
  auto m = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\nf 4 1 2\n", "obj");
  ASSERT_TRUE(m) << m.error().format();
  ASSERT_EQ(m->positions.size(), 6u);
  EXPECT_EQ(m->positions[2], glm::vec3(0, 1, 0));
  EXPECT_EQ(m->positions[3], glm::vec3(5, 5, 5));
  EXPECT_EQ(m->positions[5], glm::vec3(1, 0, 0));
}

TEST(MeshLoaderTest, PolygonsAreTriangulatedAsFans) {
  auto m = load("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", "obj");
  ASSERT_TRUE(m) << m.error().format();
  EXPECT_EQ(m->triangle_count(), 2u);
}

TEST(MeshLoaderTest, MissingNormalsAreComputedAreaWeighted) {
  // Two faces sharing vertex 1: a big one facing +z and a small one facing +x.
  auto m = load("v 0 0 0\nv 10 0 0\nv 0 10 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 5\n", "obj");
  ASSERT_TRUE(m) << m.error().format();
  EXPECT_FALSE(m->normals_from_file);
  const glm::vec3 n = m->normals[0];
  EXPECT_NEAR(glm::length(n), 1.0f, 1e-6);
  // Areas 50 and 0.5: the +z face dominates 100 to 1.
  EXPECT_NEAR(n.z / n.x, 100.0f, 1e-3);
}

TEST(MeshLoaderTest, ZeroAreaFacesGiveFiniteNormals) {
  auto m = load("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\nf 3 3 3\n", "obj");
  ASSERT_TRUE(m) << m.error().format();
  EXPECT_TRUE(all_finite(*m));
  // Vertex 3 (2,0,0) touches only degenerate faces: (0,0,0), which rasterises nothing anyway.
  EXPECT_EQ(m->normals[2], glm::vec3(0.0f));
  EXPECT_NEAR(glm::length(m->normals[0]), 1.0f, 1e-6);
}

TEST(MeshLoaderTest, NanAndInfCoordinatesAreRejected) {
  for (const char* bad : {"nan", "inf", "-inf", "1e39"}) {
    auto m = load(std::string("v 0 0 0\nv 1 0 0\nv 0 ") + bad + " 0\nf 1 2 3\n", "obj");
    ASSERT_FALSE(m) << bad;
    EXPECT_TRUE(m.error().code == ErrorCode::mesh_invalid || m.error().code == ErrorCode::mesh_parse_failed) << bad;
  }
}

// A normal whose components are tiny (their squares underflow a float) still comes out unit length.
TEST(MeshLoaderTest, TinyNormalsAreNormalisedExactly) {
  auto m = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 1e-20 1e-20 0\nvn 3e-39 0 4e-39\nf 1//1 2//2 3//1\n", "obj");
  ASSERT_TRUE(m) << m.error().format();
  for (const auto& n : m->normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f) << n.x << " " << n.y << " " << n.z;
  EXPECT_NEAR(m->normals[1].z, 0.8f, 1e-6f);
}

TEST(MeshLoaderTest, OutOfRangeIndicesAreRejected) {
  auto m = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "obj");
  ASSERT_FALSE(m);
  EXPECT_TRUE(m.error().code == ErrorCode::mesh_parse_failed || m.error().code == ErrorCode::mesh_invalid);
}

TEST(MeshLoaderTest, EmptyAndGarbageFilesAreErrors) {
  EXPECT_EQ(load("", "obj").error().code, ErrorCode::mesh_empty);
  auto only_vertices = load("v 0 0 0\nv 1 0 0\n", "obj");
  ASSERT_FALSE(only_vertices);
  EXPECT_TRUE(only_vertices.error().code == ErrorCode::mesh_empty || only_vertices.error().code == ErrorCode::mesh_parse_failed);
  auto garbage = load(std::string("\x01\x02\x03garbage", 10), "glb");
  EXPECT_FALSE(garbage);
}

TEST(MeshLoaderTest, PlyStlAndGltfLoad) {
  auto ply = load("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                  "ply");
  ASSERT_TRUE(ply) << ply.error().format();
  EXPECT_EQ(ply->triangle_count(), 1u);

  auto stl = load("solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
                  "endfacet\nendsolid t\n", "stl");
  ASSERT_TRUE(stl) << stl.error().format();
  EXPECT_EQ(stl->triangle_count(), 1u);
  EXPECT_NEAR(stl->normals[0].z, 1.0f, 1e-6);

  const std::string gltf = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
    "nodes":[{"mesh":0,"translation":[0,2,0]}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
    "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
    "bufferViews":[{"buffer":0,"byteLength":36}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}]})";
  auto g = load(gltf, "gltf");
  ASSERT_TRUE(g) << g.error().format();
  ASSERT_EQ(g->triangle_count(), 1u);
  EXPECT_EQ(g->positions[0], glm::vec3(0, 2, 0));  // the node's translation is applied
}

TEST(MeshLoaderTest, FitToStandsAnyMeshWhereTheTargetStands) {
  auto m = load("v 10 10 10\nv 30 10 10\nv 10 50 14\nf 1 2 3\n", "obj");
  ASSERT_TRUE(m);
  const scene::Bounds target{{-2, -0.5f, -1}, {4, 3.5f, 3}};  // height 4, centred on (1, 1) in x and z
  scene::fit_to(*m, target);
  const auto b = scene::bounds(*m);
  EXPECT_NEAR(b.min.y, -0.5f, 1e-6);
  EXPECT_NEAR(b.max.y, 3.5f, 1e-6);
  EXPECT_NEAR((b.min.x + b.max.x) / 2, 1.0f, 1e-6);
  EXPECT_NEAR((b.min.z + b.max.z) / 2, 1.0f, 1e-6);
  EXPECT_NEAR((b.max.x - b.min.x) / (b.max.y - b.min.y), 20.0f / 40.0f, 1e-6) << "scaled uniformly";
}

TEST(MeshLoaderTest, TriangleCapIsEnforced) {
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (int i = 0; i < 20; ++i) obj += "f 1 2 3\n";
  auto m = scene::load_mesh({reinterpret_cast<const std::uint8_t*>(obj.data()), obj.size()}, "obj", "cap.obj", {.max_triangles = 10});
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::mesh_too_large);
}

// A mesh file names other files (a glTF buffer's uri, an OBJ's mtllib): an upload must not read
// the worker's file system through them. It once rendered /etc/passwd's bytes as vertices.
TEST(MeshLoaderTest, AMeshCannotReadOtherFiles) {
  const std::string gltf = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"buffers":[{"uri":"/etc/passwd","byteLength":36}],
    "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[-1e30,-1e30,-1e30],"max":[1e30,1e30,1e30]}]})";
  auto m = load(gltf, "gltf");
  ASSERT_FALSE(m) << "read " << m->triangle_count() << " triangles out of /etc/passwd";
  EXPECT_EQ(m.error().code, ErrorCode::mesh_parse_failed);
  EXPECT_NE(m.error().message.find("/etc/passwd"), std::string::npos) << m.error().message;
  // An OBJ's material library is not read either; the geometry still loads.
  auto obj = load("mtllib /etc/passwd\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "obj");
  ASSERT_TRUE(obj) << obj.error().format();
  EXPECT_EQ(obj->triangle_count(), 1u);
}
