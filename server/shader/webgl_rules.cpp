#include "shader/webgl_rules.h"

#include <algorithm>
#include <array>
#include <span>

#include "shader/condition_value.h"
#include "shader/driver_rewrites.h"
#include "shader/glsl_lines.h"
#include "shader/link_rules.h"
#include "shader/stand_in_names.h"
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
// spells it both ways). glslang's other errors stand in its own words, which are close to the
// browser's: ANGLE's translator, which judges every WebGL shader in Chromium, grew from the same
// 3Dlabs front end.
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
    KnownError{"switch", "last case/default label not followed by statements",
               "'switch' : no statement between the last case label and the end of the switch statement "
               "(GLSL ES 3.00 section 6.2)"},
    KnownError{"sampler/image", "type requires declaration of default precision qualifier",
               "No precision specified: a sampler other than sampler2D and samplerCube has no default precision; "
               "give it one, as in `uniform mediump sampler3D s;` (GLSL ES 3.00 section 4.5.4)"},
    KnownError{"texel offset", "argument must be compile-time constant",
               "Texture offset must be a constant expression (GLSL ES 3.00 section 8.8)"},
    KnownError{"invariant", "can only apply to an output",
               "'invariant' : Cannot be qualified as invariant: only a vertex shader's outputs can be "
               "(GLSL ES 3.00 section 4.6.1)"},
    KnownError{"variable indexing sampler array", "not supported for this version",
               "'[' : array index for samplers must be constant integral expressions (GLSL ES 3.00 section 4.1.7.1)"},
    KnownError{"preprocessor evaluation", "division by 0",
               "division by zero in an #if or #elif condition: the browser evaluates every operand that && or || "
               "does not skip (GLSL ES 3.00 section 3.4)"},
    KnownError{"location", "too large for fragment output",
               "'location' : output location must be < MAX_DRAW_BUFFERS (the browser has 8 draw buffers, locations 0 to 7)"},
    KnownError{"texel offset", "value is out of range",
               "Texture offset value out of valid range: each component must lie in [-8, 7] "
               "(WebGL 2.0: invalid texture offsets)"},
};

// glslang counts only statements that leave a node behind, so it finds `case 0: ;`, `case 0: {}`
// and `case 0: int;` empty where the browser sees a statement after the label. Whether any token
// stands between the last label of the switch on `line` and its closing brace.
bool statement_after_last_label(std::string_view code, int line) {
  const std::vector<GlslToken> tokens = tokens_of(code);
  size_t k = tokens.size();
  for (size_t i = 0; i < tokens.size() && tokens[i].line <= line; ++i)
    if (tokens[i].text == "switch") k = i;
  while (k < tokens.size() && tokens[k].text != "{") ++k;
  int depth = 0, ternaries = 0;
  size_t label_end = tokens.size();
  bool in_label = false;
  for (; k < tokens.size(); ++k) {
    const std::string_view t = tokens[k].text;
    if (t == "{") ++depth;
    if (t == "}" && --depth == 0) return label_end != tokens.size() && label_end + 1 < k;
    if (depth != 1) continue;
    if (t == "case" || t == "default") in_label = true, ternaries = 0;
    else if (in_label && t == "?") ++ternaries;
    else if (in_label && t == ":" && ternaries-- == 0) in_label = false, label_end = k;
  }
  return false;
}

// An error glslang finds where the browser finds none.
bool browser_accepts(const StageInput& s, const GlslError& e) {
  if (e.token == "switch" && e.message.rfind("last case/default label not followed by statements", 0) == 0)
    return statement_after_last_label(s.facts.preprocessed.empty() ? s.source.glsl : s.facts.preprocessed, e.at.line);
  return false;
}

const KnownError* known_error(const GlslError& e) {
  for (const auto& known : kKnownErrors)
    if (e.token.rfind(known.token, 0) == 0 && e.message.rfind(known.glslang_message, 0) == 0) return &known;
  return nullptr;
}

std::vector<Diagnostic> known_errors(const StageInput& s) {
  std::vector<Diagnostic> out;
  for (const auto& e : s.facts.errors)
    if (const KnownError* known = known_error(e); known && !browser_accepts(s, e))
      out.push_back(stage_error(s, e.at, std::string(known->browser_message)));
  return out;
}

// glslang gives a line, not a column: the column is where the token it quotes first stands on
// that line (a name as a whole word), so the student's editor can point at it.
GlslPoint at_its_token(const StageInput& s, const GlslError& e) {
  if (e.at.column > 0 || e.token.empty() || e.at.line < 1) return e.at;
  const std::string_view line = line_of(s.source.glsl, e.at.line);
  const size_t at = identifier_start(e.token[0]) ? whole_word(line, e.token) : line.find(e.token);
  return at == std::string_view::npos ? e.at : GlslPoint{e.at.line, static_cast<int>(at) + 1};
}

// ShadeLab's front end judges the stage, not the driver: a driver may accept what the browser
// refuses (NVIDIA's takes `float a; a += vec2(1.0);`), so every error glslang finds refuses the
// stage. Its other errors come in glslang's words ("'token' : message"), after the rules' own,
// and only on lines no rule has already named: there the rule's words are the browser's.
void other_front_end_errors(const StageInput& s, std::vector<Diagnostic>& errors) {
  std::vector<int> named;
  for (const auto& d : errors) named.push_back(d.line);
  for (const auto& e : s.facts.errors) {
    if (known_error(e) || browser_accepts(s, e)) continue;
    Diagnostic d = stage_error(s, at_its_token(s, e), "'" + e.token + "' : " + e.message);
    if (std::find(named.begin(), named.end(), d.line) == named.end()) errors.push_back(std::move(d));
  }
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
    if (d.after_code) {
      const bool es300 = s.source.version == GlslVersion::es300;
      errors.push_back(stage_error(
          s, {d.line, 0},
          std::string("'#extension' : extension directive must occur before any non-preprocessor tokens in ") +
              (es300 ? "ESSL3 (GLSL ES 3.00: #extension comes before the first line of code; other directives may "
                       "stand between)"
                     : "ESSL1 (the browser refuses it in GLSL ES 1.00 shaders too: #extension comes before the first "
                       "line of code)")));
      continue;
    }
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

// GLSL ES 3.00 section 4.6.1: `#pragma STDGL invariant(all)` makes a vertex shader's outputs
// invariant; a fragment shader has no outputs it could bind, and the browser refuses it there
// (ES 1.00 fragment shaders keep it: it binds their varyings).
void invariant_all_rule(const StageInput& s, std::vector<Diagnostic>& errors) {
  if (s.stage != Stage::fragment || s.source.version != GlslVersion::es300) return;
  for (const int line : s.facts.invariant_all_pragmas)
    errors.push_back(stage_error(s, {line, 0}, "'invariant' : #pragma STDGL invariant(all) can not be used in fragment shader "
                                               "(GLSL ES 3.00 section 4.6.1: it binds a vertex shader's outputs)"));
}

// The locations the browser has, whatever its GPU (glsl_facts.h): a vertex input's within
// MAX_VERTEX_ATTRIBS, a fragment output's (an array's every element) within MAX_DRAW_BUFFERS.
void location_rules(const StageInput& s, std::vector<Diagnostic>& errors) {
  if (s.source.version != GlslVersion::es300) return;
  const auto at_name = [&](const GlslVariable& v) { return stage_error(s, v.at, "'" + v.name + "' : "); };
  if (s.stage == Stage::vertex)
    for (const auto& in : s.facts.inputs)
      if (in.location >= kWebglMaxVertexAttribs) {
        Diagnostic d = at_name(in);
        d.message = "'location' : Attribute location out of range: " + std::to_string(in.location) + " for '" + in.name +
                    "', where the browser has locations 0 to " + std::to_string(kWebglMaxVertexAttribs - 1) +
                    " (MAX_VERTEX_ATTRIBS)";
        errors.push_back(std::move(d));
      }
  // A single output at 8 or past it glslang refuses itself, told the browser's MAX_DRAW_BUFFERS
  // (kKnownErrors words it); an array that starts inside and runs past it is this rule's.
  if (s.stage == Stage::fragment)
    for (const auto& out : s.facts.outputs) {
      if (std::max(out.location, 0) + out.slots <= kWebglMaxDrawBuffers) continue;
      Diagnostic d = at_name(out);
      d.message += "output array locations would exceed MAX_DRAW_BUFFERS (the browser has " + std::to_string(kWebglMaxDrawBuffers) +
                   " draw buffers, locations 0 to " + std::to_string(kWebglMaxDrawBuffers - 1) + ")";
      errors.push_back(std::move(d));
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
  invariant_all_rule(s, errors);
  location_rules(s, errors);
  other_front_end_errors(s, errors);
  std::stable_sort(errors.begin(), errors.end(), [](const Diagnostic& a, const Diagnostic& b) { return a.line < b.line; });
  return errors;
}

std::vector<Diagnostic> link_rules(const StageInput& vs, const StageInput& fs) {
  std::vector<Diagnostic> out;
  for (auto& broken : link_rule_breaks(vs.facts, fs.facts, fs.source.version))
    out.push_back(located(broken.stage == Stage::vertex ? vs : fs, "link", broken.at, "error", std::move(broken.message)));
  return out;
}

Error rule_error(ErrorCode code, std::string what, std::vector<Diagnostic> diagnostics) {
  Error e = make_error(code, std::move(what) + ": " + diagnostics.front().message);
  e.diagnostics = std::move(diagnostics);
  return e;
}

// Whether an extension was left out: the stage is then another program, to be judged again.
bool rewrite_for_driver(StageInput& s) {
  if (s.facts.parsed) blank_empty_declarations_after_labels(s.source.glsl, s.facts);
  evaluate_line_directives(s.source.glsl, s.facts);
  bool left_out = false;
  int last_kept = 0;
  for (const auto& d : s.facts.extensions) {
    // `all` and `disable` change nothing the front end has not judged; Mesa refuses them after a
    // `#pragma`, where the browser takes them.
    if (d.name == "all" || d.behavior == "disable") {
      replace_line(s.source.glsl, d.line, "");
    } else if (d.behavior != "require" && !extension_supported(d.name, s.source.version)) {
      replace_line(s.source.glsl, d.line, "");
      left_out = true;
    } else {
      last_kept = d.line;
    }
  }
  if (last_kept > 0) blank_hints_before(s.source.glsl, s.facts, last_kept);
  if (s.source.version == GlslVersion::es300 && !s.facts.uniform_blocks.empty()) default_to_std140(s.source.glsl, s.facts);
  return left_out;
}

// GLSL ES 1.00: Mesa refuses `invariant gl_FragCoord;` wherever the vertex shader does not declare
// `invariant gl_Position;`, where the browser asks it only of a fragment shader that reads
// gl_FragCoord, and takes `#pragma STDGL invariant(all)` for the declaration (link_rules.h). What
// the browser runs reaches the driver without the fragment's declaration: on one GPU the values
// are the same.
void drop_builtin_invariance_the_browser_does_not_bind(const StageInput& vs, StageInput& fs) {
  if (fs.source.version != GlslVersion::es100 || fs.source.glsl.find("invariant") == std::string::npos) return;
  const auto declared = [](std::span<const GlslToken> tokens, std::string_view name) {
    for (size_t i = 0; i + 1 < tokens.size(); ++i)
      if (tokens[i].text == "invariant" && tokens[i + 1].text == name) return i;
    return tokens.size();
  };
  const auto vertex_tokens = tokens_of(vs.facts.preprocessed);
  for (const auto& [in_fragment, in_vertex] : kInvariantBuiltinPairs) {
    if (declared(vertex_tokens, in_vertex) != vertex_tokens.size()) continue;
    const auto tokens = tokens_of(fs.source.glsl);
    const size_t at = declared(tokens, in_fragment);
    if (at + 2 >= tokens.size() || tokens[at + 2].text != ";" || tokens[at + 2].line != tokens[at].line) continue;
    const std::string_view line = line_of(fs.source.glsl, tokens[at].line);
    const size_t start = static_cast<size_t>(line.data() - fs.source.glsl.data());
    for (size_t t = at; t <= at + 2; ++t)
      fs.source.glsl.replace(start + static_cast<size_t>(tokens[t].column - 1), tokens[t].text.size(), tokens[t].text.size(), ' ');
  }
}

// The browser goes on without an extension it does not support, so what that extension brings
// (ES 1.00's dFdx) is refused: the stage is judged again as the driver will get it.
std::vector<Diagnostic> judged_without_extensions(StageInput& s) {
  s.facts = read_glsl(s.source.glsl, s.stage, s.source.version);
  std::vector<Diagnostic> errors;
  other_front_end_errors(s, errors);
  return errors;
}

// `#if 0 && 1/0`: glslang divides where `&&` skips and refuses the line, the browser takes it.
// A condition in literals only is settled here, the line given to glslang and the driver as its
// value (`#if 0`), and the stage read again; a condition naming a macro stays glslang's.
bool settle_literal_conditions(StageInput& s) {
  bool settled = false;
  for (const auto& e : s.facts.errors) {
    if (e.token != "preprocessor evaluation" || e.message.rfind("division by 0", 0) != 0) continue;
    const std::string_view line = line_of(s.source.glsl, e.at.line);
    const auto tokens = tokens_of(line);
    if (tokens.size() < 3 || tokens[0].text != "#" || (tokens[1].text != "if" && tokens[1].text != "elif")) continue;
    const auto value = literal_condition_value(line.substr(static_cast<size_t>(tokens[2].column - 1)));
    if (!value) continue;
    replace_line(s.source.glsl, e.at.line, "#" + std::string(tokens[1].text) + (*value ? " 1" : " 0"));
    settled = true;
  }
  if (settled) s.facts = read_glsl(s.source.glsl, s.stage, s.source.version);
  return settled;
}

std::string_view stage_breaks(Stage stage) {
  return stage == Stage::vertex ? "the vertex shader breaks a WebGL rule" : "the fragment shader breaks a WebGL rule";
}

}  // namespace

Expected<WebglChecked> apply_webgl_rules(UnwrappedSource& vertex, UnwrappedSource& fragment, const ShaderFile& vertex_file,
                                        const ShaderFile& fragment_file) {
  WebglChecked out;
  out.renamed = rename_reserved_names(vertex.glsl, fragment.glsl, NamesFor::front_end);
  const auto refused = [&](ErrorCode code, std::string_view what, std::vector<Diagnostic> errors) {
    restore_names(errors, out.renamed);
    return rule_error(code, std::string(what), std::move(errors));
  };
  StageInput vs{Stage::vertex, vertex, vertex_file, read_glsl(vertex.glsl, Stage::vertex, vertex.version)};
  StageInput fs{Stage::fragment, fragment, fragment_file, read_glsl(fragment.glsl, Stage::fragment, fragment.version)};
  settle_literal_conditions(vs);
  settle_literal_conditions(fs);
  if (auto errors = stage_rules(vs, out.warnings); !errors.empty())
    return refused(ErrorCode::compile_failed, stage_breaks(Stage::vertex), std::move(errors));
  if (auto errors = stage_rules(fs, out.warnings); !errors.empty())
    return refused(ErrorCode::compile_failed, stage_breaks(Stage::fragment), std::move(errors));
  if (vs.facts.parsed && fs.facts.parsed)
    if (auto errors = link_rules(vs, fs); !errors.empty()) return refused(ErrorCode::link_failed, "the shaders do not link", std::move(errors));
  drop_builtin_invariance_the_browser_does_not_bind(vs, fs);
  for (StageInput* s : {&vs, &fs})
    if (rewrite_for_driver(*s))
      if (auto errors = judged_without_extensions(*s); !errors.empty())
        return refused(ErrorCode::compile_failed, stage_breaks(s->stage), std::move(errors));
  for (auto& r : rename_reserved_names(vertex.glsl, fragment.glsl, NamesFor::driver)) out.renamed.push_back(std::move(r));
  restore_names(out.warnings, out.renamed);
  out.vertex = std::move(vs.facts);
  out.fragment = std::move(fs.facts);
  return out;
}

}  // namespace shadelab::shader
