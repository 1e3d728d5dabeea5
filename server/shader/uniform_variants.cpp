#include "shader/uniform_variants.h"

#include <algorithm>
#include <map>

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

// `uniform [precision] vec3 NAME;` and nothing else.
bool plain_vec3_uniform(const GlobalStatement& s, const std::string& name) {
  if (s.names.size() != 1 || s.has_brackets || s.layout_begin != s.layout_end) return false;
  for (const auto& w : s.words)
    if (w.text != "uniform" && w.text != "vec3" && w.text != name && !is_precision(w.text)) return false;
  return s.has("uniform") && s.has("vec3");
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

std::string epilogue(const std::vector<std::string>& names, const std::string& output, int runs) {
  const std::string n = std::to_string(runs);
  std::string s = "\n// One pass for every light (ShadeLab's grader): the code above runs once per light.\n";
  for (const auto& name : names) s += "uniform highp vec3 " + variant_uniform(name) + "[" + n + "];\n";
  s += "uniform highp int " + std::string(kVariantCount) + ";\n";
  for (int k = 0; k < runs; ++k)
    s += "layout(location = " + std::to_string(k) + ") out highp vec4 shadelab_output_" + std::to_string(k) + ";\n";
  s += "void main() {\n  highp vec4 shadelab_colour[" + n + "];\n";
  s += "  for (int shadelab_k = 0; shadelab_k < " + std::string(kVariantCount) + "; ++shadelab_k) {\n";
  for (const auto& name : names) s += "    " + name + " = " + variant_uniform(name) + "[shadelab_k];\n";
  s += "    " + std::string(kRun) + "();\n    shadelab_colour[shadelab_k] = " + output + ";\n  }\n";
  for (int k = 0; k < runs; ++k) s += "  shadelab_output_" + std::to_string(k) + " = shadelab_colour[" + std::to_string(k) + "];\n";
  return s + "}\n";
}

}  // namespace

std::string variant_uniform(std::string_view name) { return std::string(kPrefix) + "variant_" + std::string(name); }

Expected<std::string> with_uniform_variants(const UnwrappedSource& vertex, const UnwrappedSource& fragment,
                                            const std::vector<std::string>& names, int runs, int max_outputs) {
  if (fragment.version != GlslVersion::es300) return declined("GLSL ES 1.00 has one output");
  if (runs < 1 || runs > max_outputs) return declined(std::to_string(runs) + " runs, " + std::to_string(max_outputs) + " outputs");
  for (const auto& w : scan_glsl(vertex.glsl).identifiers)
    if (std::find(names.begin(), names.end(), w.text) != names.end()) return declined("the vertex shader uses " + w.text);

  const GlslScan scan = scan_glsl(fragment.glsl);
  std::vector<Edit> edits;
  bool has_main = false;
  for (const auto& w : scan.identifiers) {
    if (w.text == "discard" || w.text == "gl_FragDepth") return declined("the shader uses " + w.text);
    if (w.text.compare(0, kPrefix.size(), kPrefix) == 0) return declined("the shader has a name of ShadeLab's own (" + w.text + ")");
    if (w.text == "main") {
      has_main = true;
      edits.push_back({w.offset, w.text.size(), std::string(kRun)});
    }
  }
  if (!has_main) return declined("no main");

  std::string output;
  std::map<std::string, int> declared;  // each name's plain declarations
  for (const auto& s : scan.statements) {
    if (shared_between_runs(s)) return declined("the global " + s.names.front() + " could carry one run's value into the next");
    if (s.has("out") && !s.has_parameters) {
      if (!output.empty() || s.names.size() != 1 || s.has_brackets || !s.has("vec4")) return declined("more than one vec4 output");
      output = s.names.front();
      for (const auto& w : s.words)
        if (w.text == "out" || w.text == "invariant") edits.push_back(blank(fragment.glsl, w.offset, w.text.size()));
      if (s.layout_begin != s.layout_end) edits.push_back(blank(fragment.glsl, s.layout_begin, s.layout_end - s.layout_begin));
    }
    for (const auto& name : names) {
      if (std::find(s.names.begin(), s.names.end(), name) == s.names.end()) continue;
      if (!plain_vec3_uniform(s, name)) return declined(name + " is not declared as a plain vec3 uniform");
      ++declared[name];
      for (const auto& w : s.words)
        if (w.text == "uniform") edits.push_back(blank(fragment.glsl, w.offset, w.text.size()));
    }
  }
  if (output.empty()) return declined("no output");
  for (const auto& name : names)
    if (declared[name] != 1) return declined(name + " is declared " + std::to_string(declared[name]) + " times");
  return applied(fragment.glsl, std::move(edits)) + epilogue(names, output, runs);
}

}  // namespace shadelab::shader
