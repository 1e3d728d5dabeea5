#include "repair/value_variation.h"

#include <algorithm>
#include <iterator>

namespace shadelab::repair {

namespace {

using Kind = shader::GlslToken::Kind;
using Tokens = StageVariation::Tokens;

bool one_of(std::string_view s, std::span<const std::string_view> words) { return std::find(words.begin(), words.end(), s) != words.end(); }

// The built-in functions and constructors whose value depends on their arguments alone.
constexpr std::string_view kPure[] = {
    "vec2",  "vec3",       "vec4",      "ivec2",    "ivec3",   "ivec4",  "uvec2",  "uvec3",     "uvec4",       "bvec2", "bvec3",
    "bvec4", "mat2",       "mat3",      "mat4",     "mat2x3",  "mat2x4", "mat3x2", "mat3x4",    "mat4x2",      "mat4x3", "float",
    "int",   "uint",       "bool",      "normalize", "dot",    "cross",  "reflect", "refract",  "length",      "distance", "max",
    "min",   "clamp",      "mix",       "step",     "smoothstep", "pow", "exp",    "exp2",      "log",         "log2",  "sqrt",
    "inversesqrt", "abs",  "sign",      "floor",    "ceil",    "fract",  "mod",    "sin",       "cos",         "tan",   "asin",
    "acos",  "atan",       "radians",   "degrees",  "transpose", "inverse"};
// The built-ins a fragment or a vertex has of its own.
constexpr std::string_view kPerPoint[] = {"gl_FragCoord", "gl_FrontFacing", "gl_PointCoord", "gl_VertexID", "gl_InstanceID"};
constexpr std::string_view kInputQualifiers[] = {"in", "varying", "attribute"};

bool is(Tokens t, size_t i, std::string_view s) { return i < t.size() && t[i].text == s; }

// An identifier after a `.` is a field or a swizzle (`.xyz`), not a name of the stage.
bool field(Tokens t, size_t i) { return i > 0 && is(t, i - 1, "."); }

// A name the value reads: an identifier that is not a field nor a called function.
bool read_name(Tokens t, size_t i) { return t[i].kind == Kind::identifier && !field(t, i) && !is(t, i + 1, "("); }

// The name a declaration `qualifier [precision] type name` declares, where one starts at `i`.
std::string_view declared_at(Tokens t, size_t i) {
  size_t k = i + 1;
  while (k + 1 < t.size() && t[k + 1].kind == Kind::identifier) ++k;  // precision, type
  return k > i + 1 && k < t.size() && t[k].kind == Kind::identifier ? t[k].text : std::string_view();
}

// Where an assignment's value starts, when `i` is the name it writes (`x = `, `x += `), else 0.
size_t value_start(Tokens t, size_t i) {
  if (t[i].kind != Kind::identifier || field(t, i)) return 0;
  if (is(t, i + 1, "=") && !is(t, i + 2, "=")) return i + 2;
  const bool compound = is(t, i + 1, "+") || is(t, i + 1, "-") || is(t, i + 1, "*") || is(t, i + 1, "/");
  return compound && is(t, i + 2, "=") ? i + 3 : 0;
}

}  // namespace

StageVariation::StageVariation(Tokens t) {
  for (size_t i = 0; i + 2 < t.size(); ++i) {
    if (t[i].text == "uniform") uniforms_.emplace(declared_at(t, i));
    if (one_of(t[i].text, kInputQualifiers)) inputs_.emplace(declared_at(t, i));
  }
  inputs_.erase("");
  varying_ = inputs_;
  varying_.insert(std::begin(kPerPoint), std::end(kPerPoint));
  // A name written from something that varies varies too, however many writes away.
  for (bool grew = true; grew;) {
    grew = false;
    for (size_t i = 0; i + 2 < t.size(); ++i) {
      const size_t first = value_start(t, i);
      if (first == 0 || varying_.count(t[i].text)) continue;
      size_t last = first;
      while (last < t.size() && !is(t, last, ";")) ++last;
      if (varies(t.subspan(first, last - first))) grew = varying_.emplace(t[i].text).second || grew;
    }
  }
}

bool StageVariation::constant(Tokens value) const {
  for (size_t i = 0; i < value.size(); ++i) {
    if (value[i].kind != Kind::identifier || field(value, i)) continue;
    if (is(value, i + 1, "(") ? !one_of(value[i].text, kPure) : !uniforms_.count(value[i].text)) return false;
  }
  return true;
}

bool StageVariation::varies(Tokens value) const {
  for (size_t i = 0; i < value.size(); ++i)
    if (read_name(value, i) && varying_.count(value[i].text)) return true;
  return false;
}

std::vector<std::string> StageVariation::inputs_read(Tokens value) const {
  std::vector<std::string> out;
  for (size_t i = 0; i < value.size(); ++i)
    if (read_name(value, i) && inputs_.count(value[i].text) && std::find(out.begin(), out.end(), value[i].text) == out.end())
      out.emplace_back(value[i].text);
  return out;
}

}  // namespace shadelab::repair
