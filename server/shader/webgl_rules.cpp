#include "shader/webgl_rules.h"

#include <algorithm>
#include <array>
#include <map>

#include "shader/glsl_lines.h"
#include "shader/webgl_lexical.h"

namespace shadelab::shader {

namespace {

// One stage as the rules see it.
struct StageInput {
  Stage stage;
  UnwrappedSource& source;
  const ShaderFile& file;
  GlslFacts facts;
};

Diagnostic located_in(const UnwrappedSource& source, const ShaderFile& file, std::string_view stage_name, GlslPoint at,
                      std::string severity, std::string message) {
  const LineOrigin origin = source.locate(at.line, at.column);
  return Diagnostic{std::string(stage_name), file.name, origin.file_line, at.column ? origin.file_column : 0,
                    std::move(severity), std::move(message)};
}

Diagnostic located(const StageInput& s, std::string_view stage_name, GlslPoint at, std::string severity,
                   std::string message) {
  return located_in(s.source, s.file, stage_name, at, std::move(severity), std::move(message));
}

Diagnostic stage_error(const StageInput& s, GlslPoint at, std::string message) {
  return located(s, to_string(s.stage), at, "error", std::move(message));
}

// glslang's words for the limits WebGL sets (texel offsets; Appendix A for GLSL ES 1.00) in
// the browser's words, with where the rule is written ("limitation" or "limitations": glslang
// spells it both ways). Any other glslang error is not a WebGL
// rule: the driver judges that source.
struct KnownError {
  std::string_view token, glslang_message, browser_message;
};
constexpr std::array kKnownErrors{
    KnownError{"limitation", "while loops not available",
               "'while' : This type of loop is not allowed (GLSL ES 1.00 Appendix A section 4: only for loops)"},
    KnownError{"limitation", "do-while loops not available",
               "'do' : This type of loop is not allowed (GLSL ES 1.00 Appendix A section 4: only for loops)"},
    KnownError{"limitation", "inductive loop requires a scalar 'int' or 'float' loop index",
               "'for' : Invalid type: the loop index must be one int or float (GLSL ES 1.00 Appendix A section 4)"},
    KnownError{"limitation", "inductive-loop init-declaration requires the form",
               "'for' : Invalid init declaration: declare the loop index and set it to a constant expression "
               "(GLSL ES 1.00 Appendix A section 4)"},
    KnownError{"limitation", "inductive-loop condition requires the form",
               "'for' : Invalid condition: compare the loop index with a constant expression "
               "(GLSL ES 1.00 Appendix A section 4)"},
    KnownError{"limitation", "inductive-loop termination requires the form",
               "'for' : Invalid expression: step the loop index by ++, --, += or -= a constant expression "
               "(GLSL ES 1.00 Appendix A section 4)"},
    KnownError{"limitation", "inductive loop index modified",
               "Loop index cannot be statically assigned to within the body of the loop "
               "(GLSL ES 1.00 Appendix A section 4)"},
    KnownError{"limitation", "Non-constant-index-expression",
               "'[]' : Index expression must be constant: a constant, a loop index or an expression of them "
               "(GLSL ES 1.00 Appendix A section 5)"},
    KnownError{"defined", "cannot use in preprocessor expression when expanded from macros",
               "'defined' : unexpected token after conditional expression: a macro may not bring `defined` into "
               "#if or #elif; write defined(NAME) in the directive itself (GLSL ES leaves it undefined; the browser "
               "refuses it)"},
    KnownError{"texel offset", "value is out of range",
               "Texture offset value out of valid range: each component must lie in [-8, 7] "
               "(WebGL 2.0: invalid texture offsets)"},
};

std::vector<Diagnostic> known_errors(const StageInput& s) {
  std::vector<Diagnostic> out;
  for (const auto& e : s.facts.errors)
    for (const auto& known : kKnownErrors)
      if (e.token.rfind(known.token, 0) == 0 && e.message.rfind(known.glslang_message, 0) == 0)
        out.push_back(stage_error(s, e.at, std::string(known.browser_message)));
  return out;
}

std::string operator_message(const OperatorUse& use) {
  if (use.kind == OperatorUse::Kind::sequence)
    return "',' : sequence operator is not allowed for void, arrays, or structs containing arrays (WebGL 2.0)";
  switch (use.operand) {
    case OperatorUse::Operand::array: return "'?:' : ternary operator is not allowed for arrays (WebGL 2.0)";
    case OperatorUse::Operand::structure: return "'?:' : ternary operator is not allowed for structures (WebGL)";
    case OperatorUse::Operand::void_value: return "'?:' : ternary operator is not allowed for void (WebGL 2.0)";
  }
  return {};
}

// The preprocessor's output moves words along their line; the word's column in the source is
// the first `shared` or `packed` there.
GlslPoint in_source(const std::string& glsl, GlslPoint preprocessed) {
  const std::string_view line = line_of(glsl, preprocessed.line);
  const size_t at = std::min(line.find("shared"), line.find("packed"));
  return {preprocessed.line, at == std::string_view::npos ? 0 : static_cast<int>(at) + 1};
}

// A shader may name only the extensions its page enabled, and the homework page enables none.
// What Chromium accepts anyway, probed directive by directive (tests/browser/webgl_rules.test.mjs
// keeps the cases): the image-external ones, which its video path turns on. A WebGL 2 context
// exposes none of WebGL 1's shader extensions, in either language.
bool extension_supported(std::string_view name, GlslVersion version) {
  return name == "GL_OES_EGL_image_external" || (version == GlslVersion::es300 && name == "GL_OES_EGL_image_external_essl3");
}

bool promoted_to_es300(std::string_view name) {
  return name == "GL_OES_standard_derivatives" || name == "GL_EXT_frag_depth" || name == "GL_EXT_draw_buffers" ||
         name == "GL_EXT_shader_texture_lod";
}

void layout_rules(const StageInput& s, std::vector<Diagnostic>& errors) {
  for (const auto& at : s.facts.shared_or_packed) {
    const GlslPoint where = in_source(s.source.glsl, at);
    const std::string word =
        where.column ? std::string(line_of(s.source.glsl, at.line).substr(static_cast<size_t>(where.column - 1), 6)) : "layout";
    errors.push_back(stage_error(s, where, "'" + word + "' : Only std140 layout is allowed in WebGL (WebGL 2.0: uniform block layouts)"));
  }
}

std::string malformed_extension(const ExtensionDirective& d) {
  constexpr std::string_view form = " (GLSL ES: #extension NAME : BEHAVIOR, the behavior require, enable, warn or disable)";
  switch (d.shape) {
    case ExtensionDirective::Shape::well_formed: break;
    case ExtensionDirective::Shape::unfinished:
      return "'" + d.token + "' : invalid extension directive: it ends before its name, colon or behavior" + std::string(form);
    case ExtensionDirective::Shape::name_not_identifier:
      return "'" + d.token + "' : invalid extension name: a name starts with a letter or _" + std::string(form);
    case ExtensionDirective::Shape::unexpected_token:
      return "'" + d.token + "' : unexpected token in the extension directive" + std::string(form);
    case ExtensionDirective::Shape::unknown_behavior:
      return "'" + d.token + "' : behavior invalid: '" + d.behavior + "' is not require, enable, warn or disable" +
             std::string(form);
  }
  return {};
}

// A directive out of shape fails the compile, as does `require` of an extension the browser does
// not support or of `all`; `enable` and `warn` of an unsupported one are the browser's warning.
void extension_rules(const StageInput& s, std::vector<Diagnostic>& errors, std::vector<Diagnostic>& warnings) {
  for (const auto& d : s.facts.extensions) {
    if (d.shape != ExtensionDirective::Shape::well_formed) {
      errors.push_back(stage_error(s, {d.line, d.column}, malformed_extension(d)));
      continue;
    }
    if (d.name == "all") {
      if (d.behavior == "require" || d.behavior == "enable")
        errors.push_back(stage_error(s, {d.line, 0}, "'all' : extension cannot have '" + d.behavior +
                                                         "' behavior: `all` takes warn or disable (GLSL ES: #extension all)"));
      continue;
    }
    if (d.behavior == "disable" || extension_supported(d.name, s.source.version)) continue;
    std::string message = "'" + d.name + "' : extension is not supported";
    message += promoted_to_es300(d.name)
                   ? " (a WebGL 2 context has no WebGL 1 shader extensions; GLSL ES 3.00 has this one built in)"
                   : " (WebGL lets a shader use only the extensions its page enabled)";
    if (d.behavior == "require")
      errors.push_back(stage_error(s, {d.line, 0}, std::move(message)));
    else
      warnings.push_back(located(s, to_string(s.stage), {d.line, 0}, "warning", std::move(message)));
  }
}

// Every rule one stage breaks, in line order.
std::vector<Diagnostic> stage_rules(const StageInput& s, std::vector<Diagnostic>& warnings) {
  std::vector<Diagnostic> errors = known_errors(s);
  for (auto& e : lexical_errors(s.source.glsl, s.source.version, s.facts)) errors.push_back(stage_error(s, e.at, std::move(e.message)));
  for (const auto& use : s.facts.operators) errors.push_back(stage_error(s, use.at, operator_message(use)));
  layout_rules(s, errors);
  for (const auto& at : s.facts.frag_data_nonzero)
    errors.push_back(stage_error(s, at, "'gl_FragData' : array index for gl_FragData must be constant zero "
                                        "(WebGL 2.0: GLSL ES 1.00 fragment shader output)"));
  extension_rules(s, errors, warnings);
  std::stable_sort(errors.begin(), errors.end(), [](const Diagnostic& a, const Diagnostic& b) { return a.line < b.line; });
  return errors;
}

const UniformBlock* find_block(const GlslFacts& facts, const std::string& name) {
  for (const auto& b : facts.uniform_blocks)
    if (b.name == name) return &b;
  return nullptr;
}

// GLSL ES 3.00 section 4.3.7: a block the stages share matches member for member, precisions
// included; Mesa does not compare precisions, the browser does.
std::vector<Diagnostic> block_precision_rules(const StageInput& vs, const StageInput& fs) {
  std::vector<Diagnostic> out;
  for (const auto& fb : fs.facts.uniform_blocks) {
    const UniformBlock* vb = find_block(vs.facts, fb.name);
    if (!vb || vb->members.size() != fb.members.size()) continue;
    for (size_t k = 0; k < fb.members.size(); ++k) {
      const auto &v = vb->members[k], &f = fb.members[k];
      if (v.name != f.name || v.type != f.type || v.precision == f.precision) continue;  // other differences: the driver's
      out.push_back(located(fs, "link", f.at, "error",
                            "Precisions of uniform block members differ between shaders: '" + fb.name + "." + f.name + "' is " +
                                (v.precision.empty() ? "without precision" : v.precision) + " in the vertex shader and " +
                                (f.precision.empty() ? "without precision" : f.precision) +
                                " in the fragment shader (GLSL ES 3.00 section 4.3.7)"));
    }
  }
  return out;
}

Error rule_error(ErrorCode code, std::string what, std::vector<Diagnostic> diagnostics) {
  Error e = make_error(code, std::move(what) + ": " + diagnostics.front().message);
  e.diagnostics = std::move(diagnostics);
  return e;
}

// `layout(std140) uniform;` after the directives (#version, #extension), then `#line` gives the
// next line the number it had: GLSL ES 3.00 section 3.4 numbers the line after `#line N` as N.
void default_to_std140(std::string& glsl, const GlslFacts& facts) {
  int after = 1;
  for (const auto& d : facts.extensions) after = std::max(after, d.line);
  const std::string_view line = line_of(glsl, after);
  const size_t end = static_cast<size_t>(line.data() - glsl.data()) + line.size();
  const std::string insert = "layout(std140) uniform;\n#line " + std::to_string(after + 1) + "\n";
  if (end >= glsl.size()) glsl += "\n" + insert;
  else glsl.insert(end + 1, insert);
}

void rewrite_for_driver(StageInput& s) {
  evaluate_line_directives(s.source.glsl, s.facts);
  for (const auto& d : s.facts.extensions)
    if (d.name != "all" && d.behavior != "disable" && d.behavior != "require" && !extension_supported(d.name, s.source.version))
      replace_line(s.source.glsl, d.line, "");
  if (s.source.version == GlslVersion::es300 && !s.facts.uniform_blocks.empty()) default_to_std140(s.source.glsl, s.facts);
}

}  // namespace

Expected<WebglChecked> apply_webgl_rules(UnwrappedSource& vertex, UnwrappedSource& fragment, const ShaderFile& vertex_file,
                                        const ShaderFile& fragment_file) {
  StageInput vs{Stage::vertex, vertex, vertex_file, read_glsl(vertex.glsl, Stage::vertex, vertex.version)};
  StageInput fs{Stage::fragment, fragment, fragment_file, read_glsl(fragment.glsl, Stage::fragment, fragment.version)};
  WebglChecked out;
  if (auto errors = stage_rules(vs, out.warnings); !errors.empty())
    return rule_error(ErrorCode::compile_failed, "the vertex shader breaks a WebGL rule", std::move(errors));
  if (auto errors = stage_rules(fs, out.warnings); !errors.empty())
    return rule_error(ErrorCode::compile_failed, "the fragment shader breaks a WebGL rule", std::move(errors));
  if (vs.facts.parsed && fs.facts.parsed)
    if (auto errors = block_precision_rules(vs, fs); !errors.empty())
      return rule_error(ErrorCode::link_failed, "the shaders do not link", std::move(errors));
  rewrite_for_driver(vs);
  rewrite_for_driver(fs);
  out.vertex = std::move(vs.facts);
  out.fragment = std::move(fs.facts);
  return out;
}

std::vector<Diagnostic> link_failure_causes(const WebglChecked& checked, const UnwrappedSource& fragment,
                                            const ShaderFile& fragment_file) {
  std::vector<Diagnostic> out;
  const auto cause = [&](GlslPoint at, std::string message) {
    out.push_back(located_in(fragment, fragment_file, "link", at, "error", std::move(message)));
  };

  std::map<std::string, const GlslVariable*> outputs;
  for (const auto& o : checked.vertex.outputs) outputs[o.name] = &o;
  for (const auto& in : checked.fragment.inputs) {
    const auto it = outputs.find(in.name);
    if (it == outputs.end())
      cause(in.at, "the fragment shader's input '" + in.name + "' is not an output of the vertex shader");
    else if (it->second->type != in.type)
      cause(in.at, "'" + in.name + "' is " + it->second->type + " out of the vertex shader but " + in.type + " into the fragment shader");
  }
  std::map<std::string, const GlslVariable*> uniforms;
  for (const auto& u : checked.vertex.uniforms) uniforms[u.name] = &u;
  for (const auto& u : checked.fragment.uniforms)
    if (const auto it = uniforms.find(u.name); it != uniforms.end() && it->second->type != u.type)
      cause(u.at, "the uniform '" + u.name + "' is " + it->second->type + " in the vertex shader but " + u.type + " in the fragment shader");
  for (const auto& fb : checked.fragment.uniform_blocks) {
    const UniformBlock* vb = find_block(checked.vertex, fb.name);
    if (!vb) continue;
    bool same = vb->members.size() == fb.members.size();
    for (size_t k = 0; same && k < fb.members.size(); ++k)
      same = vb->members[k].name == fb.members[k].name && vb->members[k].type == fb.members[k].type;
    if (!same) cause(fb.at, "the uniform block '" + fb.name + "' has different members in the two shaders (names, types and order must match)");
  }
  return out;
}

}  // namespace shadelab::shader
