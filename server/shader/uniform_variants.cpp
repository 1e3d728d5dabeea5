#include "shader/uniform_variants.h"

#include <algorithm>
#include <map>
#include <optional>

#include "shader/global_scan.h"

namespace shadelab::shader {

namespace {

constexpr std::string_view kPrefix = "shadelab_";
constexpr std::string_view kRun = "shadelab_run";  // the student's main, renamed

Error declined(const std::string& why) { return make_error(ErrorCode::invalid_argument, "one pass for every light: " + why); }

bool is_precision(std::string_view w) { return w == "highp" || w == "mediump" || w == "lowp"; }

// A variable at global scope that one run could write and the next read.
bool shared_between_runs(const GlobalStatement& s) {
  if (s.has_parameters || s.names.empty()) return false;
  for (std::string_view q : {"uniform", "in", "out", "const", "precision", "invariant"})
    if (s.has(q)) return false;
  return true;
}

// `uniform [precision] vec3 NAME;` or `... vec4 NAME;` and nothing else: its type, else nothing.
std::optional<std::string> plain_vector_uniform(const GlobalStatement& s, const std::string& name) {
  if (s.names.size() != 1 || s.has_brackets || s.layout_begin != s.layout_end || !s.has("uniform")) return std::nullopt;
  const std::string type = s.has("vec3") ? "vec3" : s.has("vec4") ? "vec4" : "";
  if (type.empty()) return std::nullopt;
  for (const auto& w : s.words)
    if (w.text != "uniform" && w.text != type && w.text != name && !is_precision(w.text)) return std::nullopt;
  return type;
}

// Spans blanked and words replaced, applied back to front so offsets hold.
struct Edit {
  size_t at, length;
  std::string with;
};

std::string applied(std::string_view glsl, std::vector<Edit> edits) {
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.at > b.at; });
  std::string out(glsl);
  for (const auto& e : edits) out.replace(e.at, e.length, e.with);
  return out;
}

// Spaces over a span, its line breaks kept (a layout's parentheses may hold some).
Edit blank(std::string_view glsl, size_t at, size_t length) {
  std::string spaces(glsl.substr(at, length));
  for (char& c : spaces)
    if (c != '\n') c = ' ';
  return {at, length, std::move(spaces)};
}

// (NaN, infinity) of a colour, each 0 or 1, from its bits alone (see the header).
constexpr std::string_view kNonFinite =
    "highp vec2 shadelab_non_finite(highp vec4 c) {\n"
    "  highp uvec4 bits = floatBitsToUint(c);\n"
    "  highp uvec4 all_ones = (((bits >> 23u) & 0xffu) + 1u) >> 8u;\n"
    "  highp uvec4 nan = all_ones * min(bits & 0x7fffffu, uvec4(1u));\n"
    "  highp uvec4 inf = all_ones - nan;\n"
    "  return vec2(float(max(max(nan.x, nan.y), max(nan.z, nan.w))), float(max(max(inf.x, inf.y), max(inf.z, inf.w))));\n"
    "}\n";

std::string colour(int k) { return "shadelab_colour[" + std::to_string(k) + "]"; }

std::string epilogue(const std::vector<std::string>& names, const std::map<std::string, std::string>& types, const std::string& output,
                     int runs, bool census) {
  const std::string n = std::to_string(runs);
  const VariantOutputs outputs = variant_outputs(runs, census);
  std::string s = "\n// One pass for every light (ShadeLab's grader): the code above runs once per light.\n";
  for (const auto& name : names) s += "uniform highp " + types.at(name) + " " + variant_uniform(name) + "[" + n + "];\n";
  s += "uniform highp int " + std::string(kVariantCount) + ";\n";
  for (int k = 0; k < outputs.total(); ++k)
    s += "layout(location = " + std::to_string(k) + ") out highp vec4 " +
         (k < runs ? "shadelab_output_" + std::to_string(k) : "shadelab_census_" + std::to_string(k - runs)) + ";\n";
  if (census) s += kNonFinite;
  s += "void main() {\n  highp vec4 shadelab_colour[" + n + "];\n";
  s += "  for (int shadelab_k = 0; shadelab_k < " + std::string(kVariantCount) + "; ++shadelab_k) {\n";
  for (const auto& name : names) s += "    " + name + " = " + variant_uniform(name) + "[shadelab_k];\n";
  s += "    " + std::string(kRun) + "();\n    shadelab_colour[shadelab_k] = " + output + ";\n  }\n";
  for (int k = 0; k < runs; ++k) s += "  shadelab_output_" + std::to_string(k) + " = " + colour(k) + ";\n";
  for (int j = 0; j < outputs.census; ++j) {
    const int second = 2 * j + 1;
    s += "  shadelab_census_" + std::to_string(j) + " = vec4(shadelab_non_finite(" + colour(2 * j) + "), " +
         (second < runs ? "shadelab_non_finite(" + colour(second) + ")" : "vec2(0.0)") + ");\n";
  }
  return s + "}\n";
}

}  // namespace

std::string variant_uniform(std::string_view name) { return std::string(kPrefix) + "variant_" + std::string(name); }

VariantOutputs variant_outputs(int runs, bool census) { return {runs, census ? (runs + 1) / 2 : 0}; }

Expected<std::string> with_uniform_variants(const UnwrappedSource& vertex, const UnwrappedSource& fragment,
                                            const std::vector<std::string>& names, int runs, int max_outputs, bool census) {
  if (fragment.version != GlslVersion::es300) return declined("GLSL ES 1.00 has one output");
  const int outputs = variant_outputs(runs, census).total();
  if (runs < 1 || outputs > max_outputs)
    return declined(std::to_string(runs) + " runs need " + std::to_string(outputs) + " outputs, " + std::to_string(max_outputs) + " are drawn at once");
  const bool several = runs > 1;  // what one run decides or leaves behind matters only to the next
  for (const auto& w : scan_glsl(vertex.glsl).identifiers)
    if (std::find(names.begin(), names.end(), w.text) != names.end()) return declined("the vertex shader uses " + w.text);

  const GlslScan scan = scan_glsl(fragment.glsl);
  // A macro of the student's would apply to the code appended here too: `#define floatBitsToUint(x)
  // uvec4(0u)` would blind the census to every NaN.
  if (scan.defines_macro) return declined("the shader defines a macro, which would apply to the grader's code after it");
  std::vector<Edit> edits;
  bool has_main = false;
  for (const auto& w : scan.identifiers) {
    if (several && (w.text == "discard" || w.text == "gl_FragDepth")) return declined("the shader uses " + w.text);
    if (w.text.compare(0, kPrefix.size(), kPrefix) == 0) return declined("the shader has a name of ShadeLab's own (" + w.text + ")");
    if (w.text == "main") {
      has_main = true;
      edits.push_back({w.offset, w.text.size(), std::string(kRun)});
    }
  }
  if (!has_main) return declined("no main");

  std::string output;
  std::map<std::string, int> declared;  // each name's plain declarations
  std::map<std::string, std::string> types;
  for (const auto& s : scan.statements) {
    if (several && shared_between_runs(s)) return declined("the global " + s.names.front() + " could carry one run's value into the next");
    if (s.has("out") && !s.has_parameters) {
      if (!output.empty() || s.names.size() != 1 || s.has_brackets || !s.has("vec4")) return declined("more than one vec4 output");
      output = s.names.front();
      for (const auto& w : s.words)
        if (w.text == "out" || w.text == "invariant") edits.push_back(blank(fragment.glsl, w.offset, w.text.size()));
      if (s.layout_begin != s.layout_end) edits.push_back(blank(fragment.glsl, s.layout_begin, s.layout_end - s.layout_begin));
    }
    for (const auto& name : names) {
      if (std::find(s.names.begin(), s.names.end(), name) == s.names.end()) continue;
      const auto type = plain_vector_uniform(s, name);
      if (!type) return declined(name + " is not declared as a plain vec3 or vec4 uniform");
      types[name] = *type;
      ++declared[name];
      for (const auto& w : s.words)
        if (w.text == "uniform") edits.push_back(blank(fragment.glsl, w.offset, w.text.size()));
    }
  }
  if (output.empty()) return declined("no output");
  for (const auto& name : names)
    if (declared[name] != 1) return declined(name + " is declared " + std::to_string(declared[name]) + " times");
  return applied(fragment.glsl, std::move(edits)) + epilogue(names, types, output, runs, census);
}

}  // namespace shadelab::shader
