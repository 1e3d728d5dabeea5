// The glTF check before assimp (scene/gltf_preflight.h) through load_mesh: a well-formed file in
// either container loads; every size a file declares beyond the bytes it holds is an error
// naming the field, before assimp allocates it.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "scene/mesh.h"

using namespace shadelab;
using nlohmann::json;

namespace {

// One triangle: 3 float positions and 3 ushort indices (padded to 44 bytes), as tests/fuzz's seed.
std::string triangle_buffer() {
  std::string b;
  const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t indices[] = {0, 1, 2, 0};
  b.append(reinterpret_cast<const char*>(positions), sizeof positions);
  b.append(reinterpret_cast<const char*>(indices), sizeof indices);
  return b;
}

json triangle_gltf() {
  return json::parse(R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
    "buffers":[{"byteLength":44}],
    "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
                 {"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})");
}

void put32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>(v >> (8 * i) & 0xff);
}

std::string glb(const json& gltf, const std::string& bin) {
  std::string text = gltf.dump();
  text.append(-text.size() % 4, ' ');
  std::string chunks;
  put32(chunks, static_cast<std::uint32_t>(text.size()));
  put32(chunks, 0x4E4F534A);
  chunks += text;
  put32(chunks, static_cast<std::uint32_t>(bin.size()));
  put32(chunks, 0x004E4942);
  chunks += bin;
  std::string out;
  put32(out, 0x46546C67);
  put32(out, 2);
  put32(out, static_cast<std::uint32_t>(12 + chunks.size()));
  return out + chunks;
}

Expected<scene::Mesh> load(const std::string& bytes, const std::string& format, const scene::MeshLimits& limits = {}) {
  return scene::load_mesh({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()}, format, "t." + format, limits);
}

void expect_refused(const json& gltf, const std::string& fragment, ErrorCode code = ErrorCode::mesh_parse_failed) {
  auto m = load(glb(gltf, triangle_buffer()), "glb", {.max_triangles = 1000});
  ASSERT_FALSE(m) << gltf.dump();
  EXPECT_EQ(m.error().code, code) << m.error().message;
  EXPECT_NE(m.error().message.find(fragment), std::string::npos) << m.error().message;
}

}  // namespace

TEST(GltfPreflightTest, AWellFormedFileLoadsFromEitherContainer) {
  auto binary = load(glb(triangle_gltf(), triangle_buffer()), "glb");
  ASSERT_TRUE(binary) << binary.error().format();
  EXPECT_EQ(binary->triangle_count(), 1u);
  json text = triangle_gltf();
  // base64 of the 44-byte buffer
  text["buffers"][0]["uri"] =
      "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=";
  auto embedded = load(text.dump(), "gltf");
  ASSERT_TRUE(embedded) << embedded.error().format();
  EXPECT_EQ(embedded->positions, binary->positions);
}

TEST(GltfPreflightTest, DeclaredSizesBeyondTheFileAreRefused) {
  json g = triangle_gltf();
  g["buffers"][0]["byteLength"] = 3000000000u;
  expect_refused(g, "buffers[0].byteLength: 3000000000 bytes, and the file holds 44 for it");
  g = triangle_gltf();
  g["bufferViews"][1]["byteOffset"] = 40;
  expect_refused(g, "bufferViews[1]: runs past the end of buffer 0");
  g = triangle_gltf();
  g["accessors"][0]["count"] = 4;
  expect_refused(g, "accessors[0]: 4 elements run past the end of buffer view 0");
  g = triangle_gltf();
  g["bufferViews"][0]["byteStride"] = 200;
  expect_refused(g, "accessors[0]: 3 elements run past the end of buffer view 0");
  g = triangle_gltf();
  g["accessors"][1]["sparse"] = {{"count", 9}, {"indices", {{"bufferView", 1}, {"componentType", 5123}}}, {"values", {{"bufferView", 0}}}};
  expect_refused(g, "accessors[1].sparse.count: more than the accessor's 3 elements");
  g = triangle_gltf();
  g["accessors"].push_back({{"componentType", 5126}, {"count", 3001}, {"type", "VEC3"}});  // zeros, no buffer view
  expect_refused(g, "accessors[2].count: 3001 elements, more than three per triangle", ErrorCode::mesh_too_large);
}

TEST(GltfPreflightTest, MalformedFieldsAreNamed) {
  json g = triangle_gltf();
  g["bufferViews"][0]["buffer"] = "SCALAR";
  expect_refused(g, "bufferViews[0].buffer: expected a whole number");
  g = triangle_gltf();
  g["bufferViews"][0].erase("byteLength");
  expect_refused(g, "bufferViews[0].byteLength: required");
  g = triangle_gltf();
  g["bufferViews"][0]["buffer"] = 7;
  expect_refused(g, "bufferViews[0].buffer: there is no buffer 7");
  g = triangle_gltf();
  g["accessors"][0]["bufferView"] = 5;
  expect_refused(g, "accessors[0].bufferView: there is no buffer view 5");
  g = triangle_gltf();
  g["accessors"][0]["type"] = "VEC5";
  expect_refused(g, "accessors[0]: componentType and type must be ones glTF 2.0 defines");
  g = triangle_gltf();
  g["asset"]["version"] = "1.0";
  expect_refused(g, "only glTF 2.0 is read");
  g = triangle_gltf();
  g["buffers"][0]["uri"] = "../secret.bin";
  expect_refused(g, "'../secret.bin' names another file");
}

TEST(GltfPreflightTest, ABrokenContainerIsRefused) {
  const std::string good = glb(triangle_gltf(), triangle_buffer());
  std::string longer = good;
  longer[8] = static_cast<char>(0xff);  // declares more bytes than there are
  for (const auto& [bytes, fragment] : std::vector<std::pair<std::string, std::string>>{
           {good.substr(0, 16), "not a GLB file"},
           {longer, "the GLB header declares"},
           {good.substr(0, good.size() - 8), "the GLB header declares"},
           {"glTF" + std::string("\x01\0\0\0", 4) + good.substr(8), "GLB version 1"},
           {"{\"asset\": ", "the JSON is not a valid glTF document"}}) {
    auto m = load(bytes, bytes.starts_with("{") ? "gltf" : "glb");
    ASSERT_FALSE(m) << fragment;
    EXPECT_EQ(m.error().code, ErrorCode::mesh_parse_failed);
    EXPECT_NE(m.error().message.find(fragment), std::string::npos) << m.error().message;
  }
}

// The fuzzer's find: 672 bytes of GLB for which assimp asked for 2.9 GB.
TEST(GltfPreflightTest, TheFileThatMadeAssimpAllocate3GbIsRefused) {
  std::ifstream in(std::string(SHADELAB_SOURCE_DIR) + "/tests/fuzz/regressions/mesh_loader/oom-fda11aa117de681cc4504906a7ddad087958ca1c",
                   std::ios::binary);
  ASSERT_TRUE(in);
  const std::string input{std::istreambuf_iterator<char>(in), {}};
  ASSERT_EQ(static_cast<unsigned char>(input.at(0)) % 5, 4) << "the fuzz target's selector byte picks GLB";
  auto m = load(input.substr(1), "glb");
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::mesh_parse_failed) << m.error().message;
}
