// ShadeLab's own OBJ reader (scene/obj_reader.h) through load_mesh, as a worker reads an upload:
// the built-ins' vertices are the ones the student's browser parses (strtod, then float), the
// statement forms the homework's files use, and every malformed file a structured error naming
// its line, never a crash.
#include <gtest/gtest.h>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include <glm/geometric.hpp>

#include "core/embedded_files.h"
#include "scene/mesh.h"

using namespace shadelab;

namespace {

Expected<scene::Mesh> load_obj(const std::string& text, const scene::MeshLimits& limits = {}) {
  return scene::load_mesh({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}, "obj", "test.obj", limits);
}

// The file's `v` lines as the page's loader reads them: Number(text), stored in a Float32Array.
std::vector<glm::vec3> browser_positions(const std::string& text) {
  std::vector<glm::vec3> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("v ", 0) != 0) continue;
    const char* p = line.c_str() + 2;
    glm::vec3 v;
    for (int axis = 0; axis < 3; ++axis) {
      char* end = nullptr;
      v[axis] = static_cast<float>(std::strtod(p, &end));
      p = end;
    }
    out.push_back(v);
  }
  return out;
}

bool same_bits(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_error(const std::string& text, ErrorCode code, const std::string& fragment) {
  auto m = load_obj(text);
  ASSERT_FALSE(m) << text;
  EXPECT_EQ(m.error().code, code) << text << "\n" << m.error().message;
  EXPECT_NE(m.error().message.find(fragment), std::string::npos) << text << "\n" << m.error().message;
  EXPECT_NE(m.error().message.find("test.obj"), std::string::npos) << m.error().message;
}

}  // namespace

// Every corner of the built-ins, in order, is the file's vertex as the browser parses it; assimp's
// reader (used before) put the same corners in the same order, but its fast_atof rounded some
// coordinates one float step away.
TEST(ObjReaderTest, TheBuiltinsVerticesAreTheBrowsersBitForBit) {
  for (const std::string name : {"bunny", "teapot"}) {
    const auto text = embedded_file("assets/" + name + ".obj");
    ASSERT_TRUE(text) << name;
    auto mine = load_obj(std::string(*text));
    ASSERT_TRUE(mine) << mine.error().format();
    const auto file = browser_positions(std::string(*text));

    Assimp::Importer importer;
    const aiScene* theirs = importer.ReadFileFromMemory(text->data(), text->size(), 0, "obj");
    ASSERT_TRUE(theirs && theirs->mNumMeshes == 1) << name;
    const aiMesh& m = *theirs->mMeshes[0];
    ASSERT_EQ(mine->positions.size(), m.mNumVertices) << name;
    std::istringstream faces{std::string(*text)};
    size_t corner = 0;
    for (std::string line; std::getline(faces, line);) {
      if (line.rfind("f ", 0) != 0) continue;
      std::istringstream words(line.substr(2));
      for (std::string word; words >> word; ++corner) {
        const size_t index = std::stoul(word) - 1;  // the built-ins' faces are "v//vn"
        ASSERT_LT(index, file.size());
        EXPECT_TRUE(same_bits(mine->positions[corner], file[index])) << name << " corner " << corner;
        const glm::vec3 a(m.mVertices[corner].x, m.mVertices[corner].y, m.mVertices[corner].z);
        EXPECT_LE(glm::length(a - file[index]), 1e-6f) << name << " corner " << corner;
      }
    }
    EXPECT_EQ(corner, mine->positions.size());
    EXPECT_TRUE(mine->normals_from_file);
  }
}

TEST(ObjReaderTest, EveryCornerFormAndNegativeIndices) {
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 2\nvn 0 0 -1\n";
  for (const std::string f : {"f 1//1 2//1 3//1", "f 1/1/1 2/1/1 3/1/1", "f -3//-2 -2//-2 -1//-2", "f\t1//1\t2//1   3//1\r"}) {
    auto m = load_obj(head + f + "\n");
    ASSERT_TRUE(m) << f << ": " << m.error().format();
    ASSERT_EQ(m->triangle_count(), 1u) << f;
    EXPECT_EQ(m->positions[1], glm::vec3(1, 0, 0)) << f;
    EXPECT_EQ(m->normals[2], glm::vec3(0, 0, 1)) << f << " (normalised)";
    EXPECT_TRUE(m->normals_from_file) << f;
  }
  for (const std::string f : {"f 1 2 3", "f 1/1 2/1 3/1", "f -3 -2 -1"}) {
    auto m = load_obj(head + f + "\n");
    ASSERT_TRUE(m) << f << ": " << m.error().format();
    EXPECT_FALSE(m->normals_from_file) << f << ": no corner names a normal";
    EXPECT_EQ(m->normals[0], glm::vec3(0, 0, 1)) << f << " (computed)";
  }
}

TEST(ObjReaderTest, OtherStatementsAreSkippedAndPointsAndLinesCounted) {
  auto m = load_obj("# a comment\nmtllib m.mtl\no thing\ng part\ns 1\nusemtl red\nv 0 0 0 1\nv 1 0 0 0.5 0.5 0.5\n"
                    "v 0 1 0\nvp 0.5\np 1\nl 1 2\nf 1 2\nf 1 2 3\ncstype bezier\n");
  ASSERT_TRUE(m) << m.error().format();
  EXPECT_EQ(m->triangle_count(), 1u);
  EXPECT_EQ(m->skipped_primitives, 3) << "a point, a line and a two-corner face";
}

// A corner with no normal in a file that has them takes the computed one; the others keep theirs.
TEST(ObjReaderTest, ACornerWithoutANormalIsComputed) {
  auto m = load_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 1 0 0\nf 1//1 2 3//1\n");
  ASSERT_TRUE(m) << m.error().format();
  EXPECT_EQ(m->normals[0], glm::vec3(1, 0, 0));
  EXPECT_EQ(m->normals[1], glm::vec3(0, 0, 1));
  EXPECT_EQ(m->normals[2], glm::vec3(1, 0, 0));
}

TEST(ObjReaderTest, MalformedFilesNameTheLine) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expect_error("v 1 2\n", ErrorCode::mesh_parse_failed, "line 1: a vertex needs three numbers");
  expect_error(tri + "vn 1 0\n", ErrorCode::mesh_parse_failed, "line 4: a normal needs three numbers");
  expect_error("v 1 x 3\n", ErrorCode::mesh_parse_failed, "line 1: 'x' is not a number");
  expect_error("v 1 2 3abc\n", ErrorCode::mesh_parse_failed, "'3abc' is not a number");
  expect_error(tri + "f 1 2 0\n", ErrorCode::mesh_parse_failed, "line 4: vertex indices start at 1");
  expect_error(tri + "f 1 2 a\n", ErrorCode::mesh_parse_failed, "'a' is not a vertex index");
  expect_error(tri + "f 1 2 /1\n", ErrorCode::mesh_parse_failed, "'' is not a vertex index");
  expect_error(tri + "f 1 2 3/1/1/1\n", ErrorCode::mesh_parse_failed, "has more than three parts");
  expect_error(tri + "f 1 2 99999999999999999999\n", ErrorCode::mesh_parse_failed, "is not a vertex index");
  expect_error(tri + "\n\nf 1 2 4\n", ErrorCode::mesh_invalid, "line 6: a face refers to vertex 4, and 3 are defined before it");
  expect_error(tri + "f 1 2 -4\n", ErrorCode::mesh_invalid, "vertex -4, and 3 are defined");
  expect_error("f 1 2 3\n" + tri, ErrorCode::mesh_invalid, "line 1: a face refers to vertex 1, and 0 are defined");
  expect_error(tri + "f 1//1 2//1 3//1\n", ErrorCode::mesh_invalid, "normal 1, and 0 are defined");
  expect_error("v 1e39 0 0\n", ErrorCode::mesh_invalid, "'1e39' is not a finite number a float can hold");
  expect_error("v 0 nan 0\n", ErrorCode::mesh_invalid, "'nan' is not a finite number");
}

// The limit stops reading at the face that passes it, before the corners are stored.
TEST(ObjReaderTest, TheTriangleLimitStopsTheRead) {
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 1 2 3 1 2 3\n";  // 7 triangles in one polygon
  auto m = load_obj(obj, {.max_triangles = 6});
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::mesh_too_large);
  EXPECT_NE(m.error().message.find("line 4: more than 6 triangles"), std::string::npos) << m.error().message;
  EXPECT_TRUE(load_obj(obj, {.max_triangles = 7}));
}

// The input that crashed assimp's OBJ reader (it was in tests/fuzz/contained/) is answered.
TEST(ObjReaderTest, TheFileThatCrashedAssimpIsAnError) {
  const std::string path = std::string(SHADELAB_SOURCE_DIR) + "/tests/fuzz/regressions/mesh_loader/crash-42d1c72f90c4656129f0c37d8dbc60ea9e8f3ea1";
  std::ifstream in(path, std::ios::binary);
  ASSERT_TRUE(in) << path;
  const std::string input{std::istreambuf_iterator<char>(in), {}};
  ASSERT_EQ(static_cast<unsigned char>(input.at(0)) % 5, 0) << "the fuzz target's selector byte picks OBJ";
  auto m = load_obj(input.substr(1));
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::mesh_parse_failed) << m.error().message;
}
