#include "shader/link_rules.h"

#include <map>

namespace shadelab::shader {

namespace {

constexpr std::string_view kBetween = " differ between VERTEX and FRAGMENT shaders";

// "2-element array of 3-component vector of float" -> "3-component vector of float".
std::string_view element_type(std::string_view type) {
  constexpr std::string_view array = "-element array of ";
  const size_t at = type.find(array);
  return at == std::string_view::npos ? type : type.substr(at + array.size());
}

bool is_array(std::string_view type) { return element_type(type).size() != type.size(); }

// What about two types differs, in the browser's words: "Types", "Array sizes", "Array-ness".
std::string_view type_difference(std::string_view vertex, std::string_view fragment) {
  if (is_array(vertex) != is_array(fragment)) return "Array-nesss";  // sic: Chromium's spelling
  if (is_array(vertex) && element_type(vertex) == element_type(fragment)) return "Array sizes";
  return "Types";
}

// Types as the stages must share them: precision aside, a struct by its name and its fields'
// names and types in order (glslang's words for a struct spell its fields' precisions).
bool same_type(const GlslVariable& a, const GlslVariable& b) {
  if (a.fields.empty() || b.fields.empty()) return a.type == b.type;
  if (a.struct_name != b.struct_name || a.fields.size() != b.fields.size() || is_array(a.type) != is_array(b.type) ||
      a.type.substr(0, a.type.find("structure")) != b.type.substr(0, b.type.find("structure")))
    return false;
  for (size_t k = 0; k < a.fields.size(); ++k)
    if (a.fields[k].name != b.fields[k].name || !same_type(a.fields[k], b.fields[k])) return false;
  return true;
}

// How the stages name a type in a message: a struct by its name.
std::string type_named(const GlslVariable& v) {
  if (v.fields.empty()) return v.type;
  return v.type.substr(0, v.type.find("structure")) + "struct " + v.struct_name;
}

std::string both(std::string_view vertex, std::string_view fragment) {
  return ": " + std::string(vertex) + " in the vertex shader, " + std::string(fragment) + " in the fragment shader";
}

std::string precision_words(const GlslVariable& v) { return v.precision.empty() ? "no precision" : v.precision; }

// A fragment input the code uses, against the vertex output of its name.
void match_input(const GlslVariable& in, const GlslVariable* out, GlslVersion version, std::vector<LinkRuleBreak>& breaks) {
  const auto broken = [&](std::string message) { breaks.push_back({Stage::fragment, in.at, std::move(message)}); };
  const std::string varying = "varying '" + in.name + "'";
  if (!out) {
    broken("FRAGMENT varying " + in.name + " does not match any VERTEX varying: the fragment shader reads it, and the vertex shader declares no `out` of "
           "that name (GLSL ES 3.00 section 4.3.4)");
    return;
  }
  if (!same_type(*out, in))
    broken(std::string(type_difference(out->type, in.type)) + " of " + varying + std::string(kBetween) +
           both(type_named(*out), type_named(in)));
  else if (out->flat != in.flat)
    broken("Interpolation types of " + varying + std::string(kBetween) +
           both(out->flat ? "flat" : "smooth", in.flat ? "flat" : "smooth") +
           " (GLSL ES 3.00 section 4.3.9: the stages' interpolation qualifiers must match)");
  else if (version == GlslVersion::es100 && out->invariant != in.invariant)
    broken("Invariances of " + varying + std::string(kBetween) +
           both(out->invariant ? "invariant" : "not invariant", in.invariant ? "invariant" : "not invariant") +
           " (GLSL ES 1.00 section 4.6.4)");
}

// Two precisions the stages give one uniform (or one of its struct's fields).
void match_precision(const GlslVariable& vertex, const GlslVariable& fragment, const std::string& name, GlslPoint at,
                     std::vector<LinkRuleBreak>& breaks) {
  if (!vertex.fields.empty()) {
    for (size_t k = 0; k < vertex.fields.size() && k < fragment.fields.size(); ++k)
      match_precision(vertex.fields[k], fragment.fields[k], name + "' member '" + name + "." + vertex.fields[k].name, at, breaks);
    return;
  }
  if (vertex.sampler || vertex.precision == fragment.precision) return;
  breaks.push_back({Stage::fragment, at,
                    "Precisions of uniform '" + name + "'" + std::string(kBetween) +
                        both(precision_words(vertex), precision_words(fragment)) +
                        " (GLSL ES 3.00 section 4.5.3: a uniform both stages use has one precision)"});
}

void match_uniform(const GlslVariable& vertex, const GlslVariable& fragment, std::vector<LinkRuleBreak>& breaks) {
  if (!same_type(vertex, fragment)) {
    breaks.push_back({Stage::fragment, fragment.at,
                      std::string(type_difference(vertex.type, fragment.type)) + " of uniform '" + fragment.name + "'" +
                          std::string(kBetween) + both(type_named(vertex), type_named(fragment))});
    return;
  }
  if (vertex.used && fragment.used) match_precision(vertex, fragment, fragment.name, fragment.at, breaks);
}

const UniformBlock* find_block(const GlslFacts& facts, const std::string& name) {
  for (const auto& b : facts.uniform_blocks)
    if (b.name == name) return &b;
  return nullptr;
}

// GLSL ES 3.00 section 4.3.7: a block the stages share matches member for member, precisions
// included.
void match_block(const UniformBlock& vertex, const UniformBlock& fragment, std::vector<LinkRuleBreak>& breaks) {
  const auto broken = [&](GlslPoint at, std::string message) { breaks.push_back({Stage::fragment, at, std::move(message)}); };
  bool same = vertex.members.size() == fragment.members.size();
  for (size_t k = 0; same && k < fragment.members.size(); ++k)
    same = vertex.members[k].name == fragment.members[k].name && vertex.members[k].type == fragment.members[k].type;
  if (!same) {
    broken(fragment.at, "Types of uniform block '" + fragment.name + "'" + std::string(kBetween) +
                            ": the uniform block '" + fragment.name +
                            "' has different members in the two shaders (names, types and order must match)");
    return;
  }
  for (size_t k = 0; k < fragment.members.size(); ++k) {
    const auto &v = vertex.members[k], &f = fragment.members[k];
    if (v.precision != f.precision)
      broken(f.at, "Precisions of uniform block members differ between shaders: '" + fragment.name + "." + f.name + "' is " +
                       (v.precision.empty() ? "without precision" : v.precision) + " in the vertex shader and " +
                       (f.precision.empty() ? "without precision" : f.precision) +
                       " in the fragment shader (GLSL ES 3.00 section 4.3.7)");
  }
}

template <typename T>
std::map<std::string, const T*> by_name(const std::vector<T>& all) {
  std::map<std::string, const T*> out;
  for (const auto& v : all) out.emplace(v.name, &v);
  return out;
}

}  // namespace

std::vector<LinkRuleBreak> link_rule_breaks(const GlslFacts& vertex, const GlslFacts& fragment, GlslVersion version) {
  std::vector<LinkRuleBreak> breaks;
  const auto outputs = by_name(vertex.outputs);
  for (const auto& in : fragment.inputs) {
    if (!in.used) continue;
    const auto it = outputs.find(in.name);
    match_input(in, it == outputs.end() ? nullptr : it->second, version, breaks);
  }
  const auto uniforms = by_name(vertex.uniforms);
  for (const auto& u : fragment.uniforms)
    if (const auto it = uniforms.find(u.name); it != uniforms.end()) match_uniform(*it->second, u, breaks);
  for (const auto& fb : fragment.uniform_blocks)
    if (const UniformBlock* vb = find_block(vertex, fb.name)) match_block(*vb, fb, breaks);
  return breaks;
}

}  // namespace shadelab::shader
