#include "shader/link_rules.h"

#include <array>
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

std::string array_words(int size) { return size == 0 ? "not an array" : "an array of " + std::to_string(size); }
std::string_view packing_words(bool row_major) { return row_major ? "row_major" : "column_major"; }
bool is_matrix(const GlslVariable& v) { return v.type.find("matrix") != std::string::npos; }

// GLSL ES 3.00 section 4.3.7: a block the stages share matches member for member, precisions and
// layout qualifiers included; the browser also holds the stages to one array size and to naming
// an instance in both or in neither.
void match_block(const UniformBlock& vertex, const UniformBlock& fragment, std::vector<LinkRuleBreak>& breaks) {
  const auto broken = [&](GlslPoint at, std::string message) { breaks.push_back({Stage::fragment, at, std::move(message)}); };
  const std::string block = "uniform block '" + fragment.name + "'";
  if (vertex.array_size != fragment.array_size) {
    broken(fragment.at, "Array sizes of " + block + std::string(kBetween) +
                            both(array_words(vertex.array_size), array_words(fragment.array_size)));
    return;
  }
  if (vertex.instance_name != fragment.instance_name) {
    broken(fragment.at, "Instance name qualifiers of " + block + std::string(kBetween) +
                            both(vertex.instance_name ? "an instance name" : "no instance name",
                                 fragment.instance_name ? "an instance name" : "no instance name") +
                            " (the browser takes a block with an instance name in both stages or in neither)");
    return;
  }
  bool same = vertex.members.size() == fragment.members.size();
  for (size_t k = 0; same && k < fragment.members.size(); ++k)
    same = vertex.members[k].name == fragment.members[k].name && vertex.members[k].type == fragment.members[k].type;
  if (!same) {
    broken(fragment.at, "Types of " + block + std::string(kBetween) + ": the uniform block '" + fragment.name +
                            "' has different members in the two shaders (names, types and order must match)");
    return;
  }
  constexpr std::string_view packing_rule =
      " (GLSL ES 3.00 section 4.3.7: a block's members match in their layout qualifiers; a block's `row_major` or "
      "`column_major`, or the stage's `layout(row_major) uniform;`, is each member's unless the member names its own)";
  if (vertex.row_major != fragment.row_major) {
    broken(fragment.at, "Matrix Packings of " + block + std::string(kBetween) +
                            both(packing_words(vertex.row_major), packing_words(fragment.row_major)) + std::string(packing_rule));
    return;
  }
  for (size_t k = 0; k < fragment.members.size(); ++k) {
    const auto &v = vertex.members[k], &f = fragment.members[k];
    if (v.precision != f.precision)
      broken(f.at, "Precisions of uniform block members differ between shaders: '" + fragment.name + "." + f.name + "' is " +
                       (v.precision.empty() ? "without precision" : v.precision) + " in the vertex shader and " +
                       (f.precision.empty() ? "without precision" : f.precision) +
                       " in the fragment shader (GLSL ES 3.00 section 4.3.7)");
    else if (is_matrix(f) && v.row_major != f.row_major)
      broken(f.at, "Matrix Packings of " + block + " member '" + fragment.name + "." + f.name + "'" + std::string(kBetween) +
                       both(packing_words(v.row_major), packing_words(f.row_major)) + std::string(packing_rule));
  }
}

// A block without an instance name puts its members among the program's global names (GLSL ES
// 3.00 section 4.3.7), where the other stage's uniforms and such blocks' members are too.
struct GlobalName {
  std::string name;
  GlslPoint at;
};

// A block's members as global names, a struct member once (its fields are flattened as "s.x").
std::vector<GlobalName> global_names(const UniformBlock& block) {
  std::vector<GlobalName> out;
  for (const auto& m : block.members) {
    const std::string name = m.name.substr(0, m.name.find('.'));
    if (out.empty() || out.back().name != name) out.push_back({name, m.at});
  }
  return out;
}

void name_conflict(GlslPoint at, const std::string& name, std::vector<LinkRuleBreak>& breaks) {
  breaks.push_back({Stage::fragment, at,
                    "Name conflicts between a uniform and a uniform block field: " + name +
                        " (GLSL ES 3.00 section 4.3.7: a block without an instance name makes its members global names, "
                        "one per program)"});
}

void match_global_names(const GlslFacts& vertex, const GlslFacts& fragment, std::vector<LinkRuleBreak>& breaks) {
  for (const auto& fb : fragment.uniform_blocks) {
    if (fb.instance_name) continue;
    for (const auto& m : global_names(fb)) {
      for (const auto& u : vertex.uniforms)
        if (u.name == m.name) name_conflict(m.at, m.name, breaks);
      for (const auto& vb : vertex.uniform_blocks) {
        if (vb.instance_name || vb.name == fb.name) continue;
        for (const auto& vm : global_names(vb))
          if (vm.name == m.name)
            breaks.push_back({Stage::fragment, m.at,
                              "Ambiguous field '" + m.name + "' in blocks '" + vb.name + "' (VERTEX shader) and '" + fb.name +
                                  "' (FRAGMENT shader) which don't have instance names (GLSL ES 3.00 section 4.3.7: "
                                  "their members are global names, one per program)"});
      }
    }
  }
  for (const auto& vb : vertex.uniform_blocks) {
    if (vb.instance_name) continue;
    for (const auto& m : global_names(vb))
      for (const auto& u : fragment.uniforms)
        if (u.name == m.name) name_conflict(u.at, u.name, breaks);
  }
}

// GLSL ES 1.00 section 4.6.4: gl_FragCoord may be invariant only where gl_Position is, and
// gl_PointCoord only where gl_PointSize is (the browser checks it where the fragment shader reads
// them; `#pragma STDGL invariant(all)` makes a vertex shader's built-ins invariant).
void match_invariant_builtins(const GlslFacts& vertex, const GlslFacts& fragment, std::vector<LinkRuleBreak>& breaks) {
  const auto invariant_in_vertex = [&](std::string_view name) {
    if (!vertex.invariant_all_pragmas.empty()) return true;
    for (const auto& b : vertex.invariant_builtins_used)
      if (b.name == name) return true;
    return false;
  };
  for (const auto& b : fragment.invariant_builtins_used)
    for (const auto& [in_fragment, in_vertex] : kInvariantBuiltinPairs)
      if (b.name == in_fragment && !invariant_in_vertex(in_vertex))
        breaks.push_back({Stage::fragment, b.at,
                          std::string(in_fragment) + " can only be declared invariant if and only if " + std::string(in_vertex) +
                              " is declared invariant (GLSL ES 1.00 section 4.6.4)"});
}

// The browser's vertex inputs: each location range within MAX_VERTEX_ATTRIBS, no two overlapping
// ranges, and all of them (used or not) within MAX_VERTEX_ATTRIBS locations.
void match_vertex_inputs(const GlslFacts& vertex, std::vector<LinkRuleBreak>& breaks) {
  int total = 0;
  for (const auto& in : vertex.inputs) {
    const auto broken = [&](std::string message) { breaks.push_back({Stage::vertex, in.at, std::move(message)}); };
    if (in.location >= 0 && in.location < kWebglMaxVertexAttribs && in.location + in.slots > kWebglMaxVertexAttribs)
      broken("Attribute (" + in.name + ") at location " + std::to_string(in.location) + " is too big to fit: it takes " +
             std::to_string(in.slots) + " locations, and the browser has " + std::to_string(kWebglMaxVertexAttribs));
    total += in.slots;
    if (total > kWebglMaxVertexAttribs && total - in.slots <= kWebglMaxVertexAttribs)
      broken("Too many attributes (" + in.name + "): the vertex shader's inputs take " + std::to_string(total) +
             " locations or more, and the browser has " + std::to_string(kWebglMaxVertexAttribs));
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
  match_global_names(vertex, fragment, breaks);
  if (version == GlslVersion::es100) match_invariant_builtins(vertex, fragment, breaks);
  match_vertex_inputs(vertex, breaks);
  return breaks;
}

}  // namespace shadelab::shader
