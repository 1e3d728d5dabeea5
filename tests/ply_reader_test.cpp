// ShadeLab's own PLY reader (scene/ply_reader.h) through load_mesh, as a worker reads an upload:
// the three encodings give the mesh the same triangles, assimp agrees on well-formed files, and
// every malformed one is a mesh_parse_failed naming where and why, never a crash or a spin.
#include <gtest/gtest.h>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include <bit>
#include <cstdio>
#include <cstring>

#include <glm/geometric.hpp>

#include "scene/mesh.h"
#include "support/test_support.h"

using namespace shadelab;

namespace {

Expected<scene::Mesh> load_ply(const std::string& bytes) {
  return scene::load_mesh({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()}, "ply", "test.ply");
}

enum class Encoding { ascii, little, big };

template <class T>
void put(std::string& out, T value, Encoding e) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof raw);
  if ((e == Encoding::big) != (std::endian::native == std::endian::big))
    for (size_t i = 0; i < sizeof raw / 2; ++i) std::swap(raw[i], raw[sizeof raw - 1 - i]);
  out.append(raw, sizeof raw);
}

// `mesh` as a PLY file: every corner its own vertex (position, normal and a colour to skip),
// faces in order, an extra element after them (edges) that the reader must skip.
std::string to_ply(const scene::Mesh& mesh, Encoding e) {
  const char* format[] = {"ascii", "binary_little_endian", "binary_big_endian"};
  std::string out = std::string("ply\nformat ") + format[static_cast<int>(e)] + " 1.0\ncomment written by ply_reader_test\n" +
                    "element vertex " + std::to_string(mesh.positions.size()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
                    "property float nx\nproperty float ny\nproperty float nz\n"
                    "element face " + std::to_string(mesh.triangle_count()) +
                    "\nproperty list uchar int vertex_indices\nproperty list ushort float texcoord\n"
                    "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  char text[160];
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3 p = mesh.positions[i], n = mesh.normals[i];
    if (e == Encoding::ascii) {
      std::snprintf(text, sizeof text, "%.9g %.9g %.9g 200 %.9g %.9g %.9g\n", p.x, p.y, p.z, n.x, n.y, n.z);
      out += text;
      continue;
    }
    for (float f : {p.x, p.y, p.z}) put(out, f, e);
    put(out, std::uint8_t{200}, e);
    for (float f : {n.x, n.y, n.z}) put(out, f, e);
  }
  for (std::int32_t t = 0; t < static_cast<std::int32_t>(mesh.triangle_count()); ++t) {
    if (e == Encoding::ascii) {
      out += "3 " + std::to_string(3 * t) + " " + std::to_string(3 * t + 1) + " " + std::to_string(3 * t + 2) + " 2 0.5 0.25\n";
      continue;
    }
    put(out, std::uint8_t{3}, e);
    for (std::int32_t k = 0; k < 3; ++k) put(out, 3 * t + k, e);
    put(out, std::uint16_t{2}, e);
    for (float f : {0.5f, 0.25f}) put(out, f, e);
  }
  if (e == Encoding::ascii) return out + "0 1\n";
  put(out, std::int32_t{0}, e);
  put(out, std::int32_t{1}, e);
  return out;
}

const std::string kQuadAndTriangle =
    "ply\r\nformat ascii 1.0\r\nelement vertex 5\r\nproperty double x\r\nproperty double y\r\nproperty double z\r\n"
    "element face 3\r\nproperty list uchar uint vertex_index\r\nend_header\r\n"
    "0 0 0\r\n1 0 0\r\n1 1 0\r\n0 1 0\r\n0 0 1\r\n4 0 1 2 3\r\n3 0 1 4\r\n2 0 4\r\n";

}  // namespace

TEST(PlyReaderTest, TheBunnyReadsTheSameInAsciiLittleAndBigEndian) {
  const scene::Mesh* bunny = &testkit::builtin("bunny");
  for (const Encoding e : {Encoding::ascii, Encoding::little, Encoding::big}) {
    auto m = load_ply(to_ply(*bunny, e));
    ASSERT_TRUE(m) << m.error().format();
    EXPECT_TRUE(m->normals_from_file);
    ASSERT_EQ(m->positions.size(), bunny->positions.size());
    for (size_t i = 0; i < m->positions.size(); ++i) {
      ASSERT_EQ(m->positions[i], bunny->positions[i]) << "corner " << i << " encoding " << static_cast<int>(e);
      ASSERT_NEAR(glm::length(m->normals[i] - bunny->normals[i]), 0.f, 1e-6f) << "corner " << i;
    }
  }
}

TEST(PlyReaderTest, PolygonsFanLikeAssimpReadsThemAndPointsAndLinesAreSkipped) {
  auto m = load_ply(kQuadAndTriangle);
  ASSERT_TRUE(m) << m.error().format();
  EXPECT_EQ(m->triangle_count(), 3u);  // the quad as two, the triangle; the line is skipped
  EXPECT_EQ(m->skipped_primitives, 1);
  EXPECT_FALSE(m->normals_from_file);
  // assimp's reader (the one ShadeLab used before) on the same file: the same corners in order.
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFileFromMemory(kQuadAndTriangle.data(), kQuadAndTriangle.size(), 0, "ply");
  ASSERT_TRUE(scene && scene->mNumMeshes == 1);
  const aiMesh& a = *scene->mMeshes[0];
  std::vector<glm::vec3> fanned;
  for (unsigned f = 0; f < a.mNumFaces; ++f)
    for (unsigned k = 1; k + 1 < a.mFaces[f].mNumIndices; ++k)
      for (unsigned idx : {a.mFaces[f].mIndices[0], a.mFaces[f].mIndices[k], a.mFaces[f].mIndices[k + 1]})
        fanned.emplace_back(a.mVertices[idx].x, a.mVertices[idx].y, a.mVertices[idx].z);
  EXPECT_EQ(m->positions, fanned);
}

TEST(PlyReaderTest, AMalformedFileIsAParseErrorThatSaysWhereAndWhy) {
  const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const struct {
    std::string bytes, expected;
  } cases[] = {
      {"plx\nformat ascii 1.0\nend_header\n", "line 1 of the PLY header"},
      {"ply\nformat ascii 2.0\nend_header\n", "line 2 of the PLY header"},
      {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", "a property before any element"},
      {"ply\nformat ascii 1.0\nelement vertex -3\nend_header\n", "not a whole number"},
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nelement vertex 1\nend_header\n", "declared twice"},
      {"ply\nformat ascii 1.0\nelement face 1\nproperty list float int vertex_indices\nend_header\n", "integer type"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n", "unknown type 'quad'"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "no 'end_header'"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n", "no 'vertex' element with properties x, y and z"},
      // The contained assimp crash (tests/fuzz/regressions/mesh_loader/crash-b6aea877…): a header
      // whose keywords are cut.
      {"ply\nformat binary_little_endian 1.0\nelemevbsp tentrex 3\nend_header\n", "unknown keyword 'elemevbsp'"},
      {header + std::string(36, '\0'), "element 'face', record 1 of 1"},
      {header + std::string(36, '\0') + "\x03", "the file ends inside list"},
      {header + std::string(36, '\0') + "\x03\xff\xff\xff\xff" + std::string(8, '\0'), "vertex index -1 is negative"},
      // A count no file could hold is refused before a loop runs over it.
      {"ply\nformat ascii 1.0\nelement vertex 18446744073709551615\nproperty float x\nproperty float y\nproperty float z\n"
       "end_header\n0 0 0\n",
       "too short for 18446744073709551615 records"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty uchar x\nproperty float y\nproperty float z\nend_header\n300 0 0\n",
       "holds no number at property 'x'"},
  };
  for (const auto& c : cases) {
    auto m = load_ply(c.bytes);
    ASSERT_FALSE(m) << c.expected;
    EXPECT_EQ(m.error().code, ErrorCode::mesh_parse_failed) << m.error().format();
    EXPECT_NE(m.error().message.find(c.expected), std::string::npos) << m.error().message;
  }
}

TEST(PlyReaderTest, IndicesOutsideTheFileAndNonFiniteCoordinatesAreInvalid) {
  auto out_of_range = load_ply("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                               "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  ASSERT_FALSE(out_of_range);
  EXPECT_EQ(out_of_range.error().code, ErrorCode::mesh_invalid);
  EXPECT_NE(out_of_range.error().message.find("refers to vertex 4 of 3"), std::string::npos) << out_of_range.error().message;
  auto nan = load_ply("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
  ASSERT_FALSE(nan);
  EXPECT_EQ(nan.error().code, ErrorCode::mesh_invalid);
}

TEST(PlyReaderTest, OnlyTheDocumentedFormatsAreRead) {
  const std::string off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";  // assimp reads OFF; ShadeLab does not offer it
  auto m = scene::load_mesh({reinterpret_cast<const std::uint8_t*>(off.data()), off.size()}, "off", "shape.off");
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::mesh_parse_failed);
  EXPECT_NE(m.error().message.find("OBJ, PLY, STL, glTF and GLB"), std::string::npos) << m.error().message;
  // The name picks the only reader a file meets: assimp would otherwise try all its readers by
  // content when the named one declines (its PLY reader crashed on a "glb" file that way).
  const std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nend_header\n";
  for (const char* format : {"glb", "gltf", "obj", "stl"}) {
    auto other = scene::load_mesh({reinterpret_cast<const std::uint8_t*>(ply.data()), ply.size()}, format, "mesh." + std::string(format));
    ASSERT_FALSE(other) << format;
    EXPECT_TRUE(other.error().code == ErrorCode::mesh_parse_failed || other.error().code == ErrorCode::mesh_empty) << other.error().format();
  }
}
