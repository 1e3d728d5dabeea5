#include "scene/ply_reader.h"

#include <array>
#include <bit>
#include <charconv>
#include <cstring>
#include <optional>
#include <vector>

namespace shadelab::scene {

namespace {

// ---- the header -------------------------------------------------------------------------------

enum class Scalar { i8, u8, i16, u16, i32, u32, f32, f64 };

struct ScalarName {
  std::string_view name;
  Scalar type;
};
// Both spellings the format's users write: the original names and the sized ones.
constexpr ScalarName kScalars[] = {{"char", Scalar::i8},    {"int8", Scalar::i8},     {"uchar", Scalar::u8},
                                   {"uint8", Scalar::u8},   {"short", Scalar::i16},   {"int16", Scalar::i16},
                                   {"ushort", Scalar::u16}, {"uint16", Scalar::u16},  {"int", Scalar::i32},
                                   {"int32", Scalar::i32},  {"uint", Scalar::u32},    {"uint32", Scalar::u32},
                                   {"float", Scalar::f32},  {"float32", Scalar::f32}, {"double", Scalar::f64},
                                   {"float64", Scalar::f64}};

size_t size_of(Scalar s) {
  switch (s) {
    case Scalar::i8: case Scalar::u8: return 1;
    case Scalar::i16: case Scalar::u16: return 2;
    case Scalar::i32: case Scalar::u32: case Scalar::f32: return 4;
    case Scalar::f64: return 8;
  }
  return 8;
}

bool is_integer(Scalar s) { return s != Scalar::f32 && s != Scalar::f64; }

// The values an integer type holds (an ASCII body may write any number where one is expected).
bool holds(Scalar s, double v) {
  constexpr std::pair<double, double> kRanges[] = {{-128, 127}, {0, 255}, {-32768, 32767}, {0, 65535}, {-2147483648.0, 2147483647.0},
                                                   {0, 4294967295.0}};
  if (!is_integer(s)) return true;
  const auto [lo, hi] = kRanges[static_cast<size_t>(s)];
  return v >= lo && v <= hi && v == static_cast<double>(static_cast<std::int64_t>(v));
}

std::optional<Scalar> scalar_named(std::string_view name) {
  for (const auto& s : kScalars)
    if (s.name == name) return s.type;
  return std::nullopt;
}

// What a property's values are for.
enum class Role { skip, x, y, z, nx, ny, nz, face_corners };
constexpr size_t kRoles = static_cast<size_t>(Role::face_corners) + 1;

struct Property {
  std::string name;
  Scalar type = Scalar::f32;       // each value's (a list's items')
  std::optional<Scalar> list_count; // set for a list: the type of its length
  Role role = Role::skip;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

enum class Encoding { ascii, little_endian, big_endian };

struct Header {
  Encoding encoding = Encoding::ascii;
  std::vector<Element> elements;
  size_t body_offset = 0;
};

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

// Header errors name the line, as the student's editor counts it.
struct HeaderReader {
  std::string_view bytes;
  const std::string& name;
  size_t line_number = 0;

  Error fail(const std::string& why) const {
    return make_error(ErrorCode::mesh_parse_failed, "'" + name + "': line " + std::to_string(line_number) + " of the PLY header: " + why);
  }

  Expected<Encoding> format(const std::vector<std::string_view>& w) const {
    if (w.size() != 3 || w[2] != "1.0") return fail("expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
    if (w[1] == "ascii") return Encoding::ascii;
    if (w[1] == "binary_little_endian") return Encoding::little_endian;
    if (w[1] == "binary_big_endian") return Encoding::big_endian;
    return fail("unknown format '" + std::string(w[1]) + "'");
  }

  Expected<Element> element(const std::vector<std::string_view>& w, const std::vector<Element>& seen) const {
    Element e;
    if (w.size() != 3) return fail("expected 'element <name> <count>'");
    e.name = w[1];
    const auto [end, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
    if (ec != std::errc() || end != w[2].data() + w[2].size()) return fail("the count of element '" + e.name + "' is not a whole number");
    for (const auto& s : seen)
      if (s.name == e.name) return fail("element '" + e.name + "' is declared twice");
    return e;
  }

  Expected<Property> property(const std::vector<std::string_view>& w) const {
    Property p;
    const bool list = w.size() >= 2 && w[1] == "list";
    if (w.size() != (list ? 5u : 3u)) return fail("expected 'property <type> <name>' or 'property list <count type> <type> <name>'");
    if (list) {
      p.list_count = scalar_named(w[2]);
      if (!p.list_count || !is_integer(*p.list_count)) return fail("a list's length must have an integer type, not '" + std::string(w[2]) + "'");
    }
    const auto type = scalar_named(w[list ? 3 : 1]);
    if (!type) return fail("unknown type '" + std::string(w[list ? 3 : 1]) + "'");
    p.type = *type;
    p.name = w.back();
    return p;
  }

  // One header line's declaration (format, element or property) added to `h`.
  Status declare(const std::vector<std::string_view>& w, Header& h, bool& have_format) const {
    if (w[0] == "format") {
      auto encoding = format(w);
      if (!encoding) return encoding.error();
      h.encoding = *encoding;
      have_format = true;
    } else if (w[0] == "element") {
      auto e = element(w, h.elements);
      if (!e) return e.error();
      h.elements.push_back(std::move(*e));
    } else if (w[0] == "property") {
      if (h.elements.empty()) return fail("a property before any element");
      auto p = property(w);
      if (!p) return p.error();
      h.elements.back().properties.push_back(std::move(*p));
    } else {
      return fail("unknown keyword '" + std::string(w[0]) + "'");
    }
    return Ok{};
  }

  Expected<Header> read() {
    Header h;
    bool have_format = false;
    for (size_t at = 0, end; (end = bytes.find('\n', at)) != std::string_view::npos; at = end + 1) {
      std::string_view line = bytes.substr(at, end - at);
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      const auto w = words(line);
      if (++line_number == 1) {
        if (w.size() != 1 || w[0] != "ply") return fail("a PLY file starts with a line 'ply'");
      } else if (!w.empty() && w[0] == "end_header") {
        if (!have_format) return fail("the header has no 'format' line");
        h.body_offset = end + 1;
        return h;
      } else if (!w.empty() && w[0] != "comment" && w[0] != "obj_info") {
        if (auto declared = declare(w, h, have_format); !declared) return declared.error();
      }
    }
    ++line_number;
    return fail("the header has no 'end_header' line");
  }
};

// ---- what is kept -------------------------------------------------------------------------------

Role role_of(const Element& e, const Property& p) {
  if (e.name == "vertex" && !p.list_count) {
    constexpr std::pair<std::string_view, Role> kVertex[] = {{"x", Role::x},   {"y", Role::y},   {"z", Role::z},
                                                             {"nx", Role::nx}, {"ny", Role::ny}, {"nz", Role::nz}};
    for (const auto& [n, r] : kVertex)
      if (p.name == n) return r;
  }
  if (e.name == "face" && p.list_count && is_integer(p.type) && (p.name == "vertex_indices" || p.name == "vertex_index"))
    return Role::face_corners;
  return Role::skip;
}

struct Roles {
  bool positions = false, normals = false;
};

Roles assign_roles(Header& h) {
  Roles found;
  for (auto& e : h.elements) {
    std::array<bool, kRoles> seen{};
    for (auto& p : e.properties) {
      p.role = role_of(e, p);
      if (seen[static_cast<size_t>(p.role)]) p.role = Role::skip;  // the first x wins, as in assimp
      seen[static_cast<size_t>(p.role)] = true;
    }
    if (e.name != "vertex") continue;
    found.positions = seen[static_cast<size_t>(Role::x)] && seen[static_cast<size_t>(Role::y)] && seen[static_cast<size_t>(Role::z)];
    found.normals = seen[static_cast<size_t>(Role::nx)] && seen[static_cast<size_t>(Role::ny)] && seen[static_cast<size_t>(Role::nz)];
    if (!found.normals)
      for (auto& p : e.properties)
        if (p.role == Role::nx || p.role == Role::ny || p.role == Role::nz) p.role = Role::skip;
  }
  return found;
}

// ---- the body -------------------------------------------------------------------------------

// One value at a time from the body; a number read is a double (every PLY scalar fits one
// exactly), and nullopt where the body ends or holds no number there.
class AsciiValues {
 public:
  explicit AsciiValues(std::string_view body) : body_(body) {}
  std::optional<double> next(Scalar type) {
    while (at_ < body_.size() && (body_[at_] == ' ' || body_[at_] == '\t' || body_[at_] == '\r' || body_[at_] == '\n')) ++at_;
    const char* first = body_.data() + at_;
    const char* last = body_.data() + body_.size();
    double value = 0;
    const auto [end, ec] = std::from_chars(first, last, value);
    if (ec != std::errc() || end == first || !holds(type, value)) return std::nullopt;
    at_ = static_cast<size_t>(end - body_.data());
    return value;
  }
  size_t left() const { return body_.size() - at_; }

 private:
  std::string_view body_;
  size_t at_ = 0;
};

class BinaryValues {
 public:
  BinaryValues(std::string_view body, bool big_endian) : body_(body), swap_(big_endian != (std::endian::native == std::endian::big)) {}
  std::optional<double> next(Scalar type) {
    const size_t size = size_of(type);
    if (body_.size() - at_ < size) return std::nullopt;
    unsigned char raw[8];
    std::memcpy(raw, body_.data() + at_, size);
    at_ += size;
    if (swap_)
      for (size_t i = 0; i < size / 2; ++i) std::swap(raw[i], raw[size - 1 - i]);
    return decode(type, raw);
  }
  size_t left() const { return body_.size() - at_; }

 private:
  template <class T>
  static double as(const unsigned char* raw) {
    T value;
    std::memcpy(&value, raw, sizeof value);
    return static_cast<double>(value);
  }
  static double decode(Scalar type, const unsigned char* raw) {
    switch (type) {
      case Scalar::i8: return as<std::int8_t>(raw);
      case Scalar::u8: return as<std::uint8_t>(raw);
      case Scalar::i16: return as<std::int16_t>(raw);
      case Scalar::u16: return as<std::uint16_t>(raw);
      case Scalar::i32: return as<std::int32_t>(raw);
      case Scalar::u32: return as<std::uint32_t>(raw);
      case Scalar::f32: return as<float>(raw);
      case Scalar::f64: return as<double>(raw);
    }
    return 0;
  }
  std::string_view body_;
  size_t at_ = 0;
  bool swap_;
};

template <class Values>
struct BodyReader {
  Values values;
  const std::string& name;
  IndexedMesh& mesh;
  bool has_normals;  // the vertex element has nx, ny and nz

  Error fail(const Element& e, std::uint64_t record, const std::string& why) const {
    return make_error(ErrorCode::mesh_parse_failed, "'" + name + "': PLY element '" + e.name + "', record " +
                                                        std::to_string(record + 1) + " of " + std::to_string(e.count) + ": " + why);
  }

  Status list(const Element& e, std::uint64_t record, const Property& p) {
    const auto length = values.next(*p.list_count);
    if (!length || *length < 0) return fail(e, record, "a list's length is missing or negative");
    const bool corners = p.role == Role::face_corners;
    for (double k = 0; k < *length; ++k) {
      const auto v = values.next(p.type);
      if (!v) return fail(e, record, "the file ends inside list '" + p.name + "'");
      if (!corners) continue;
      if (*v < 0) return fail(e, record, "vertex index " + std::to_string(static_cast<long long>(*v)) + " is negative");
      mesh.corners.push_back(static_cast<std::uint32_t>(*v));
    }
    // Every item took a byte at least, so a list read whole is shorter than the 4 GB file cap.
    if (corners) mesh.face_sizes.push_back(static_cast<std::uint32_t>(*length));
    return Ok{};
  }

  Status record(const Element& e, std::uint64_t record) {
    glm::vec3 position{0.f}, normal{0.f};
    for (const auto& p : e.properties) {
      if (p.list_count) {
        if (auto s = list(e, record, p); !s) return s;
        continue;
      }
      const auto v = values.next(p.type);
      if (!v) return fail(e, record, "the file ends or holds no number at property '" + p.name + "'");
      const float f = static_cast<float>(*v);
      switch (p.role) {
        case Role::x: position.x = f; break;
        case Role::y: position.y = f; break;
        case Role::z: position.z = f; break;
        case Role::nx: normal.x = f; break;
        case Role::ny: normal.y = f; break;
        case Role::nz: normal.z = f; break;
        default: break;
      }
    }
    if (e.name == "vertex") {
      mesh.positions.push_back(position);
      if (has_normals) mesh.normals.push_back(normal);
    }
    return Ok{};
  }

  Status element(const Element& e) {
    // Every record of an element with properties takes at least a byte per property, so a count
    // the rest of the file cannot hold is refused before any loop (no 2^64-record spin).
    if (e.properties.empty()) return Ok{};
    if (e.count > values.left() / e.properties.size()) return fail(e, 0, "the file is too short for " + std::to_string(e.count) + " records");
    for (std::uint64_t r = 0; r < e.count; ++r)
      if (auto s = record(e, r); !s) return s;
    return Ok{};
  }
};

template <class Values>
Expected<IndexedMesh> read_body(const Header& h, Values values, const Roles& roles, const std::string& name) {
  IndexedMesh mesh;
  mesh.name = name;
  BodyReader<Values> reader{std::move(values), name, mesh, roles.normals};
  for (const auto& e : h.elements)
    if (auto s = reader.element(e); !s) return s.error();
  return mesh;
}

}  // namespace

Expected<IndexedMesh> read_ply(std::string_view bytes, const std::string& name) {
  HeaderReader header_reader{bytes, name};
  auto header = header_reader.read();
  if (!header) return header.error();
  const Roles roles = assign_roles(*header);
  if (!roles.positions)
    return make_error(ErrorCode::mesh_parse_failed, "'" + name + "': the PLY file has no 'vertex' element with properties x, y and z");
  const std::string_view body = bytes.substr(header->body_offset);
  if (header->encoding == Encoding::ascii) return read_body(*header, AsciiValues(body), roles, name);
  return read_body(*header, BinaryValues(body, header->encoding == Encoding::big_endian), roles, name);
}

}  // namespace shadelab::scene
