#include "scene/obj_reader.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <optional>
#include <vector>

namespace shadelab::scene {

namespace {

constexpr std::uint32_t kNoNormal = UINT32_MAX;

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// A statement's words, split on spaces and tabs (OBJ has no quoting).
class Words {
 public:
  explicit Words(std::string_view line) : rest_(line) {}
  std::optional<std::string_view> next() {
    while (!rest_.empty() && is_space(rest_.front())) rest_.remove_prefix(1);
    if (rest_.empty()) return std::nullopt;
    size_t end = 0;
    while (end < rest_.size() && !is_space(rest_[end])) ++end;
    const std::string_view word = rest_.substr(0, end);
    rest_.remove_prefix(end);
    return word;
  }

 private:
  std::string_view rest_;
};

// JavaScript's Number() then a Float32Array element: the double nearest the text, then the
// float nearest that double, which is what the page uploads.
std::optional<float> parse_coordinate(std::string_view word) {
  if (!word.empty() && word.front() == '+') word.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (ec != std::errc{} || end != word.data() + word.size()) return std::nullopt;
  return static_cast<float>(value);
}

std::optional<std::int64_t> parse_index(std::string_view word) {
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (ec != std::errc{} || end != word.data() + word.size() || word.empty()) return std::nullopt;
  return value;
}

class ObjParser {
 public:
  ObjParser(const std::string& name, const MeshLimits& limits) : name_(name), limits_(limits) {}

  Expected<IndexedMesh> read(std::string_view bytes) {
    while (!bytes.empty()) {
      const size_t end = std::min(bytes.find('\n'), bytes.size());
      ++line_;
      if (auto s = statement(bytes.substr(0, end)); !s) return s.error();
      bytes.remove_prefix(std::min(end + 1, bytes.size()));
    }
    return assemble();
  }

 private:
  Status statement(std::string_view line) {
    Words words(line);
    const auto keyword = words.next();
    if (!keyword) return Ok{};
    if (*keyword == "v") return vector3(words, positions_, "vertex");
    if (*keyword == "vn") return vector3(words, normals_, "normal");
    if (*keyword == "f") return face(words);
    if (*keyword == "p" || *keyword == "l") ++other_primitives_;
    return Ok{};  // vt, o, g, s, usemtl, mtllib, comments and the rest: nothing to draw
  }

  Status vector3(Words& words, std::vector<glm::vec3>& into, const char* what) {
    glm::vec3 v;
    for (int axis = 0; axis < 3; ++axis) {
      const auto word = words.next();
      if (!word) return fail(ErrorCode::mesh_parse_failed, std::string("a ") + what + " needs three numbers");
      const auto number = parse_coordinate(*word);
      if (!number) return fail(ErrorCode::mesh_parse_failed, "'" + std::string(*word) + "' is not a number");
      if (!std::isfinite(*number))
        return fail(ErrorCode::mesh_invalid, "'" + std::string(*word) + "' is not a finite number a float can hold");
      v[axis] = *number;
    }
    into.push_back(v);  // a 4th number (w, or the first of a colour) is ignored, as in the browser
    return Ok{};
  }

  Status face(Words& words) {
    std::uint32_t size = 0;
    while (const auto word = words.next()) {
      if (auto s = corner(*word); !s) return s;
      ++size;
    }
    if (size >= 3) {
      triangles_ += size - 2;
      if (triangles_ > limits_.max_triangles)
        return fail(ErrorCode::mesh_too_large, "more than " + std::to_string(limits_.max_triangles) + " triangles");
    }
    face_sizes_.push_back(size);
    return Ok{};
  }

  // "v", "v/vt", "v//vn" or "v/vt/vn"; the texture coordinate is not used.
  Status corner(std::string_view word) {
    std::string_view parts[3];
    size_t count = 0;
    for (size_t at = 0; at <= word.size(); ++count) {
      const size_t slash = std::min(word.find('/', at), word.size());
      if (count == 3) return fail(ErrorCode::mesh_parse_failed, "'" + std::string(word) + "' has more than three parts");
      parts[count] = word.substr(at, slash - at);
      at = slash + 1;
    }
    auto position = resolve(parts[0], positions_.size(), "vertex");
    if (!position) return position.error();
    corner_positions_.push_back(*position);
    if (count < 3 || parts[2].empty()) {
      corner_normals_.push_back(kNoNormal);
      return Ok{};
    }
    auto normal = resolve(parts[2], normals_.size(), "normal");
    if (!normal) return normal.error();
    corner_normals_.push_back(*normal);
    any_normal_ = true;
    return Ok{};
  }

  // A 1-based index, or a negative one counting back from the latest; only what came before.
  Expected<std::uint32_t> resolve(std::string_view word, size_t defined, const char* what) {
    const auto index = parse_index(word);
    if (!index) return fail(ErrorCode::mesh_parse_failed, "'" + std::string(word) + "' is not a " + what + " index");
    if (*index == 0) return fail(ErrorCode::mesh_parse_failed, std::string(what) + " indices start at 1; 0 names no " + what);
    const std::int64_t n = static_cast<std::int64_t>(defined);
    const std::int64_t zero_based = *index > 0 ? *index - 1 : n + *index;
    if (zero_based < 0 || zero_based >= n)
      return fail(ErrorCode::mesh_invalid, "a face refers to " + std::string(what) + " " + std::string(word) + ", and " +
                                               std::to_string(n) + " are defined before it");
    return static_cast<std::uint32_t>(zero_based);
  }

  // Shared positions when no corner names a normal; else one vertex per corner, since OBJ
  // indexes positions and normals separately.
  IndexedMesh assemble() {
    IndexedMesh out;
    out.name = name_;
    out.face_sizes = std::move(face_sizes_);
    out.other_primitives = other_primitives_;
    if (!any_normal_) {
      out.positions = std::move(positions_);
      out.corners = std::move(corner_positions_);
      return out;
    }
    out.positions.reserve(corner_positions_.size());
    out.normals.reserve(corner_positions_.size());
    for (size_t k = 0; k < corner_positions_.size(); ++k) {
      out.positions.push_back(positions_[corner_positions_[k]]);
      out.normals.push_back(corner_normals_[k] == kNoNormal ? glm::vec3(0.f) : normals_[corner_normals_[k]]);
    }
    out.corners.resize(corner_positions_.size());
    std::iota(out.corners.begin(), out.corners.end(), 0u);
    return out;
  }

  Error fail(ErrorCode code, const std::string& why) const {
    const std::string where = "line " + std::to_string(line_) + ": ";
    // load_mesh names the file in every error but a parse error, which names it itself.
    return make_error(code, code == ErrorCode::mesh_parse_failed ? "'" + name_ + "': " + where + why : where + why);
  }

  const std::string& name_;
  const MeshLimits& limits_;
  size_t line_ = 0;
  std::vector<glm::vec3> positions_, normals_;
  std::vector<std::uint32_t> corner_positions_, corner_normals_, face_sizes_;
  std::uint64_t triangles_ = 0;
  int other_primitives_ = 0;
  bool any_normal_ = false;
};

}  // namespace

Expected<IndexedMesh> read_obj(std::string_view bytes, const std::string& name, const MeshLimits& limits) {
  return ObjParser(name, limits).read(bytes);
}

}  // namespace shadelab::scene
