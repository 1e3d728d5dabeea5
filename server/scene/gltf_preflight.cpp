#include "scene/gltf_preflight.h"

#include <cstdint>
#include <cstring>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/client_json.h"

namespace shadelab::scene {

namespace {

using nlohmann::json;

// No size in an upload comes near this; values above it are refused before any arithmetic, so
// products of two of them stay far inside 64 bits.
constexpr std::uint64_t kLargestSize = std::uint64_t{1} << 40;

struct Glb {
  std::string_view json_text;
  std::optional<std::uint64_t> bin_size;  // the BIN chunk's length, when there is one
};

std::uint32_t le32(std::string_view bytes, size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = v << 8 | static_cast<unsigned char>(bytes[at + i]);
  return v;
}

// Why a glTF file cannot be read, naming the field, as load_mesh reports it.
class Fail {
 public:
  explicit Fail(const std::string& name) : name_(name) {}
  Error operator()(const std::string& where, const std::string& why, ErrorCode code = ErrorCode::mesh_parse_failed) const {
    return make_error(code, "'" + name_ + "': glTF " + where + (where.empty() ? "" : ": ") + why);
  }

 private:
  const std::string& name_;
};

Expected<Glb> split_glb(std::string_view bytes, const Fail& fail) {
  constexpr std::uint32_t kMagic = 0x46546C67, kJson = 0x4E4F534A, kBin = 0x004E4942;
  if (bytes.size() < 20 || le32(bytes, 0) != kMagic) return fail("", "not a GLB file (it starts with the 'glTF' magic and a header)");
  if (le32(bytes, 4) != 2) return fail("", "GLB version " + std::to_string(le32(bytes, 4)) + "; only version 2 is read");
  const std::uint64_t length = le32(bytes, 8);
  if (length > bytes.size()) return fail("", "the GLB header declares " + std::to_string(length) + " bytes and the file has " +
                                                 std::to_string(bytes.size()));
  bytes = bytes.substr(0, length);
  const std::uint64_t json_length = le32(bytes, 12);
  if (le32(bytes, 16) != kJson || 20 + json_length > bytes.size())
    return fail("", "the GLB's first chunk is not a JSON chunk that fits in the file");
  Glb glb{bytes.substr(20, json_length), std::nullopt};
  const size_t next = 20 + json_length;
  if (next + 8 <= bytes.size() && le32(bytes, next + 4) == kBin) {
    const std::uint64_t bin_length = le32(bytes, next);
    if (next + 8 + bin_length > bytes.size()) return fail("", "the GLB's BIN chunk runs past the end of the file");
    glb.bin_size = bin_length;
  }
  return glb;
}

// A non-negative whole number no larger than kLargestSize, or `fallback` when absent.
Expected<std::uint64_t> size_field(const json& object, const char* key, const std::string& where, const Fail& fail,
                                   std::optional<std::uint64_t> fallback = std::nullopt) {
  const auto it = object.find(key);
  if (it == object.end()) {
    if (fallback) return *fallback;
    return fail(where + "." + key, "required");
  }
  if (!it->is_number_unsigned() || it->get<std::uint64_t>() > kLargestSize)
    return fail(where + "." + key, "expected a whole number of at most 2^40, got " + describe_client_value(*it));
  return it->get<std::uint64_t>();
}

const json& array_field(const json& root, const char* key) {
  static const json empty = json::array();
  const auto it = root.find(key);
  return it != root.end() && it->is_array() ? *it : empty;
}

// Each element of the array `key` (none when absent) as an object, with its path ("buffers[2]");
// the first problem `check` finds ends the walk.
template <class Check>
Status each_object(const json& root, const char* key, const Fail& fail, Check check) {
  const json& list = array_field(root, key);
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string where = std::string(key) + "[" + std::to_string(i) + "]";
    if (!list[i].is_object()) return fail(where, "expected an object");
    if (auto s = check(list[i], i, where); !s) return s;
  }
  return Ok{};
}

// The bytes that hold a buffer: the GLB's BIN chunk (no uri) or a base64 data: URI's payload.
Expected<std::uint64_t> buffer_capacity(const json& buffer, size_t index, const std::optional<std::uint64_t>& bin_size,
                                        const std::string& where, const Fail& fail) {
  const auto uri = buffer.find("uri");
  if (uri == buffer.end()) {
    if (index == 0 && bin_size) return *bin_size;
    return fail(where, "has no uri and is not the GLB's BIN chunk");
  }
  if (!uri->is_string()) return fail(where + ".uri", "expected a string");
  const std::string& text = uri->get_ref<const std::string&>();
  const size_t comma = text.find(',');
  if (!text.starts_with("data:") || comma == std::string::npos || text.rfind(";base64", comma) == std::string::npos)
    return fail(where + ".uri", "'" + text.substr(0, 80) + "' names another file; an upload is one file (a GLB, or buffers as base64 data: URIs)");
  return (text.size() - comma - 1) / 4 * 3 + 3;
}

Expected<std::vector<std::uint64_t>> check_buffers(const json& root, const std::optional<std::uint64_t>& bin_size, const Fail& fail) {
  std::vector<std::uint64_t> lengths;
  const auto checked = each_object(root, "buffers", fail, [&](const json& buffer, size_t i, const std::string& where) -> Status {
    auto length = size_field(buffer, "byteLength", where, fail);
    if (!length) return length.error();
    auto capacity = buffer_capacity(buffer, i, bin_size, where, fail);
    if (!capacity) return capacity.error();
    if (*length > *capacity)
      return fail(where + ".byteLength", std::to_string(*length) + " bytes, and the file holds " + std::to_string(*capacity) + " for it");
    lengths.push_back(*length);
    return Ok{};
  });
  if (!checked) return checked.error();
  return lengths;
}

struct View {
  std::uint64_t length = 0;
  std::uint64_t stride = 0;  // 0: tightly packed
};

Expected<std::vector<View>> check_views(const json& root, const std::vector<std::uint64_t>& buffers, const Fail& fail) {
  std::vector<View> views;
  const auto checked = each_object(root, "bufferViews", fail, [&](const json& view, size_t, const std::string& where) -> Status {
    auto buffer = size_field(view, "buffer", where, fail);
    if (!buffer) return buffer.error();
    if (*buffer >= buffers.size()) return fail(where + ".buffer", "there is no buffer " + std::to_string(*buffer));
    auto offset = size_field(view, "byteOffset", where, fail, 0);
    auto length = size_field(view, "byteLength", where, fail);
    auto stride = size_field(view, "byteStride", where, fail, 0);
    for (const auto* f : {&offset, &length, &stride})
      if (!*f) return f->error();
    if (*offset + *length > buffers[*buffer]) return fail(where, "runs past the end of buffer " + std::to_string(*buffer));
    views.push_back({*length, *stride});
    return Ok{};
  });
  if (!checked) return checked.error();
  return views;
}

std::uint64_t component_size(std::uint64_t type) {
  switch (type) {
    case 5120: case 5121: return 1;  // BYTE, UNSIGNED_BYTE
    case 5122: case 5123: return 2;  // SHORT, UNSIGNED_SHORT
    case 5125: case 5126: return 4;  // UNSIGNED_INT, FLOAT
    default: return 0;
  }
}

std::uint64_t components(const json& type) {
  constexpr std::pair<const char*, std::uint64_t> kTypes[] = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
                                                              {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
  if (!type.is_string()) return 0;
  for (const auto& [name, n] : kTypes)
    if (type.get_ref<const std::string&>() == name) return n;
  return 0;
}

// `count` elements of `element` bytes at `offset` in a view, `stride` apart when it has one.
Status fits_in_view(const json& object, const std::string& where, std::uint64_t count, std::uint64_t element,
                    const std::vector<View>& views, const Fail& fail) {
  const auto view_index = object.find("bufferView");
  if (view_index == object.end()) return Ok{};
  auto index = size_field(object, "bufferView", where, fail);
  if (!index) return index.error();
  if (*index >= views.size()) return fail(where + ".bufferView", "there is no buffer view " + std::to_string(*index));
  auto offset = size_field(object, "byteOffset", where, fail, 0);
  if (!offset) return offset.error();
  const View& view = views[*index];
  const std::uint64_t stride = view.stride ? view.stride : element;
  if (count > 0 && *offset + stride * (count - 1) + element > view.length)
    return fail(where, std::to_string(count) + " elements run past the end of buffer view " + std::to_string(*index));
  return Ok{};
}

Status check_sparse(const json& sparse, const std::string& where, std::uint64_t count, std::uint64_t element,
                    const std::vector<View>& views, const Fail& fail) {
  if (!sparse.is_object()) return fail(where, "expected an object");
  auto sparse_count = size_field(sparse, "count", where, fail);
  if (!sparse_count) return sparse_count.error();
  if (*sparse_count > count) return fail(where + ".count", "more than the accessor's " + std::to_string(count) + " elements");
  const auto indices = sparse.find("indices"), values = sparse.find("values");
  if (indices == sparse.end() || !indices->is_object() || values == sparse.end() || !values->is_object())
    return fail(where, "needs objects 'indices' and 'values'");
  auto index_type = size_field(*indices, "componentType", where + ".indices", fail);
  if (!index_type) return index_type.error();
  if (auto s = fits_in_view(*indices, where + ".indices", *sparse_count, component_size(*index_type), views, fail); !s) return s;
  return fits_in_view(*values, where + ".values", *sparse_count, element, views, fail);
}

Status check_accessors(const json& root, const std::vector<View>& views, const MeshLimits& limits, const Fail& fail) {
  return each_object(root, "accessors", fail, [&](const json& accessor, size_t, const std::string& where) -> Status {
    auto count = size_field(accessor, "count", where, fail);
    auto type = size_field(accessor, "componentType", where, fail);
    for (const auto* f : {&count, &type})
      if (!*f) return f->error();
    const std::uint64_t element = component_size(*type) * components(accessor.value("type", json()));
    if (element == 0) return fail(where, "componentType and type must be ones glTF 2.0 defines");
    // An accessor without a buffer view is zeros assimp allocates: bounded by the triangle limit.
    if (*count > 3 * std::uint64_t{limits.max_triangles})
      return fail(where + ".count", std::to_string(*count) + " elements, more than three per triangle of the limit (" +
                                        std::to_string(limits.max_triangles) + ")", ErrorCode::mesh_too_large);
    if (auto s = fits_in_view(accessor, where, *count, element, views, fail); !s) return s;
    if (const auto sparse = accessor.find("sparse"); sparse != accessor.end())
      if (auto s = check_sparse(*sparse, where + ".sparse", *count, element, views, fail); !s) return s;
    return Ok{};
  });
}

}  // namespace

Status check_gltf(std::string_view bytes, bool binary, const std::string& name, const MeshLimits& limits) {
  const Fail fail(name);
  Glb glb{bytes, std::nullopt};
  if (binary) {
    auto split = split_glb(bytes, fail);
    if (!split) return split.error();
    glb = *split;
  }
  if (auto within = check_json_budget(glb.json_text, "the glTF's JSON"); !within) return fail("", within.error().message);
  const json root = json::parse(glb.json_text, nullptr, false);
  if (root.is_discarded() || !root.is_object()) return fail("", "the JSON is not a valid glTF document");
  const auto asset = root.find("asset");
  if (asset == root.end() || !asset->is_object() || !asset->value("version", json()).is_string() ||
      !asset->value("version", std::string()).starts_with("2."))
    return fail("asset.version", "only glTF 2.0 is read (asset.version \"2.0\")");
  auto buffers = check_buffers(root, glb.bin_size, fail);
  if (!buffers) return buffers.error();
  auto views = check_views(root, *buffers, fail);
  if (!views) return views.error();
  return check_accessors(root, *views, limits, fail);
}

}  // namespace shadelab::scene
