// WebGL 2's shader rules through the renderer's compile (glslang's AST, then the real driver):
// every case of tests/webgl_rules/cases.json, accepted or refused as the browser does (the
// browser test checks Chromium's verdicts on the same file), with the message and the line.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdlib>

#include "shader/condition_value.h"
#include "shader/glsl_lines.h"
#include "shader/webgl_rules.h"
#include "support/files.h"
#include "support/test_support.h"

using namespace shadelab;
using nlohmann::json;

namespace {

std::string joined(const json& lines) {
  std::string out;
  for (const auto& line : lines) out += line.get<std::string>() + "\n";
  return out;
}

json cases() {
  return json::parse(testkit::read_text(testkit::source_dir() / "tests/webgl_rules/cases.json"))["cases"];
}

// What ShadeLab refuses before any compiler runs (a misplaced #version) the browser reports as a
// failed compile.
std::string verdict_of(const Expected<render::CompileReport>& r) {
  if (r) return "accepted";
  const ErrorCode code = r.error().code;
  if (code == ErrorCode::missing_version || code == ErrorCode::shader_source_invalid) return "compile_failed";
  return std::string(to_string(code));
}

// A fragment shader beside a minimal ES 3.00 vertex shader, through the renderer's compile.
Expected<render::CompileReport> compile_fragment(const std::string& name, const std::string& fragment) {
  return testkit::shared_renderer().compile({"v.glsl", "#version 300 es\nvoid main() { gl_Position = vec4(0.0); }\n"},
                                            {name, fragment});
}

const Diagnostic* first_error(const Error& e) {
  for (const auto& d : e.diagnostics)
    if (d.severity == "error") return &d;
  return nullptr;
}

// The first error of a fragment shader the compile must refuse (empty, and the test failed, when
// it was accepted or had no error diagnostic).
Diagnostic refusal(const std::string& name, const std::string& fragment) {
  const auto r = compile_fragment(name, fragment);
  if (r) {
    ADD_FAILURE() << name << " was accepted";
    return {};
  }
  const Diagnostic* d = first_error(r.error());
  if (!d) ADD_FAILURE() << r.error().format();
  return d ? *d : Diagnostic{};
}

// Whether this process runs over tests/driver/accepts_all.cpp (label webgl_rules_any_driver).
bool over_a_driver_that_accepts_all() {
  const char* preload = std::getenv("LD_PRELOAD");
  return preload && std::string(preload).find("accepts_all") != std::string::npos;
}

// Whether the driver under the renderer is Mesa's (the "mesa" marks of cases.json are its
// refusals; another driver may run those pairs, or refuse them too: packed runs on a GPU,
// tools/gpu_check/).
bool driver_is_mesa() { return testkit::shared_renderer().context_info().gl_version.find("Mesa") != std::string::npos; }

}  // namespace

TEST(WebglRulesTest, EveryCaseGetsTheBrowsersVerdictMessageAndLine) {
  const json all = cases();
  ASSERT_GE(all.size(), 30u);
  for (const auto& c : all) {
    SCOPED_TRACE(c["name"].get<std::string>());
    const auto r = testkit::shared_renderer().compile({"rule_vert.glsl", joined(c["vertex"])},
                                                      {"rule_frag.glsl", joined(c["fragment"])});
    // A case Mesa refuses though the browser runs it: this server's limit, said as such.
    // Another driver may run it or refuse it; either way the student is not charged.
    const bool driver_may_refuse = c.contains("mesa") && !over_a_driver_that_accepts_all();
    const std::string verdict = verdict_of(r);
    if (driver_may_refuse && driver_is_mesa()) ASSERT_EQ(verdict, c["mesa"]) << (r ? "" : r.error().format());
    else if (driver_may_refuse && verdict == c["mesa"]) continue;
    else ASSERT_EQ(verdict, c["verdict"]) << (r ? "" : r.error().format());
    if (r || driver_may_refuse) continue;
    const Diagnostic* d = first_error(r.error());
    ASSERT_NE(d, nullptr) << r.error().format();
    EXPECT_NE(d->message.find(c["message"].get<std::string>()), std::string::npos) << d->format();
    EXPECT_EQ(d->line, c["line"].get<int>()) << d->format();
    EXPECT_EQ(d->file, c.value("in", "fragment") == "vertex" ? "rule_vert.glsl" : "rule_frag.glsl");
  }
}

// The rules read the JS module the student edits, and name lines of that file.
TEST(WebglRulesTest, AViolationInAJsModuleIsLocatedInTheModule) {
  const std::string fragment =
      "// phong_frag.js\nexport default `#version 300 es\nprecision mediump float;\nout vec4 c;\n"
      "void main() { float a[2], b[2]; float d[2] = true ? a : b; c = vec4(d[0]); }\n`;\n";
  const Diagnostic d = refusal("phong_frag.js", fragment);
  EXPECT_EQ(d.file, "phong_frag.js");
  EXPECT_EQ(d.line, 5);
  EXPECT_EQ(d.column, 51);  // the `?`
}

// `case 0: int;` is a label's statement to the browser and none to NVIDIA's driver: the driver is
// given `case 0: ;`, the same program with every column in place. Elsewhere the words stay.
TEST(WebglRulesTest, AnEmptyDeclarationAfterALabelReachesTheDriverAsAnEmptyStatement) {
  const std::string vertex_text = "#version 300 es\nvoid main() { gl_Position = vec4(0.0); }\n";
  const std::string fragment_text =
      "#version 300 es\nprecision mediump float;\nout vec4 color;\nuniform int u;\nvoid main() {\n"
      "  int;\n  switch (u) {\n    case 0:\n      highp int;\n    case 1: vec3;\n    default: float x; x = 1.0; /* c */ float;\n  }\n"
      "  color = vec4(1.0);\n}\n";
  const shader::ShaderFile vertex_file{"v.glsl", vertex_text}, fragment_file{"f.glsl", fragment_text};
  auto vertex = shader::unwrap(vertex_file, shader::Stage::vertex);
  auto fragment = shader::unwrap(fragment_file, shader::Stage::fragment);
  ASSERT_TRUE(vertex && fragment);
  const auto checked = shader::apply_webgl_rules(*vertex, *fragment, vertex_file, fragment_file);
  ASSERT_TRUE(checked) << checked.error().format();
  const auto lines = shader::lines_of(fragment->glsl);
  ASSERT_GE(lines.size(), 11u);
  EXPECT_EQ(lines[5], "  int;");                  // not after a label: a declaration where one may stand
  EXPECT_EQ(lines[8], "               ;");        // `highp int;` blanked, the `;` in its column
  EXPECT_EQ(lines[9], "    case 1:     ;");
  EXPECT_EQ(lines[10], "    default: float x; x = 1.0; /* c */ float;");  // not after a label
  EXPECT_TRUE(compile_fragment("f.glsl", fragment_text)) << "the browser runs it";
}

// What the browser runs and Mesa refuses reaches the driver as the same program, every line in
// its place: `#extension all` and a hint `#pragma` before a kept extension left out, a literal
// `#if` condition that glslang cannot evaluate given as its value, and (GLSL ES 1.00) an
// `invariant gl_FragCoord;` the browser does not bind without its declaration.
TEST(WebglRulesTest, WhatMesaRefusesAndTheBrowserRunsReachesTheDriverRewrittenInPlace) {
  const auto rewritten = [](const std::string& vertex_text, const std::string& fragment_text) {
    const shader::ShaderFile vertex_file{"v.glsl", vertex_text}, fragment_file{"f.glsl", fragment_text};
    auto vertex = shader::unwrap(vertex_file, shader::Stage::vertex);
    auto fragment = shader::unwrap(fragment_file, shader::Stage::fragment);
    EXPECT_TRUE(vertex && fragment);
    const auto checked = shader::apply_webgl_rules(*vertex, *fragment, vertex_file, fragment_file);
    EXPECT_TRUE(checked) << checked.error().format();
    EXPECT_TRUE(testkit::shared_renderer().compile(vertex_file, fragment_file)) << "the browser runs it";
    std::vector<std::string> lines;
    for (const auto line : shader::lines_of(fragment->glsl)) lines.emplace_back(line);
    return lines;
  };
  const std::string es300_vertex = "#version 300 es\nvoid main() { gl_Position = vec4(0.0); }\n";
  const auto es300 = rewritten(es300_vertex,
                               "#version 300 es\n#pragma optimize(off)\n#extension all : warn\n"
                               "#extension GL_OES_EGL_image_external_essl3 : enable\n#if 0 && 1 / 0\n#endif\n"
                               "precision mediump float;\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n");
  ASSERT_GE(es300.size(), 9u);
  EXPECT_EQ(es300[1], "");  // the hint before an extension the driver gets
  EXPECT_EQ(es300[2], "");  // `all` changes nothing the front end has not judged
  EXPECT_EQ(es300[3], "#extension GL_OES_EGL_image_external_essl3 : enable");
  EXPECT_EQ(es300[4], "#if 0");
  EXPECT_EQ(es300[8], "void main() { c = vec4(1.0); }");
  const auto es100 = rewritten("attribute vec4 p;\nvoid main() { gl_Position = p; }\n",
                               "precision mediump float;\ninvariant gl_FragCoord;\nvoid main() { gl_FragColor = vec4(1.0); }\n");
  ASSERT_GE(es100.size(), 3u);
  EXPECT_EQ(es100[1], std::string(23, ' '));  // never read: the browser does not bind it
  EXPECT_EQ(es100[2], "void main() { gl_FragColor = vec4(1.0); }");
}

// An `#if` in literals, as C reads it: `&&` and `||` skip the side their left decides (a division
// by zero there is never evaluated); anything it cannot read alone (a name, a division that
// counts, a shift past 31, a broken expression) stays the compiler's.
TEST(WebglRulesTest, ALiteralConditionIsReadAsCReadsIt) {
  using shader::literal_condition_value;
  EXPECT_EQ(literal_condition_value("0 && 1 / 0"), 0);
  EXPECT_EQ(literal_condition_value("1 || 1 % 0"), 1);
  EXPECT_EQ(literal_condition_value("(0 && 1/0) || 1"), 1);
  EXPECT_EQ(literal_condition_value("(1 + 2) * 3 == 9 && 7 / 2 == 3"), 1);
  EXPECT_EQ(literal_condition_value("0x10 == 16 && 010 == 8"), 1);
  EXPECT_EQ(literal_condition_value("-1 < 0 && !0 && ~0 == -1 && (1 << 4) == 16"), 1);
  EXPECT_EQ(literal_condition_value("1 | 2 ^ 3 & 1"), 1 | (2 ^ (3 & 1)));
  EXPECT_EQ(literal_condition_value("1 && 1 / 0"), std::nullopt);
  EXPECT_EQ(literal_condition_value("0 || 1 % (1 - 1)"), std::nullopt);
  EXPECT_EQ(literal_condition_value("X && 1"), std::nullopt);
  EXPECT_EQ(literal_condition_value("defined(X) && X / 0"), std::nullopt);
  EXPECT_EQ(literal_condition_value("1 << 40"), std::nullopt);
  EXPECT_EQ(literal_condition_value("1 +"), std::nullopt);
  EXPECT_EQ(literal_condition_value("(1"), std::nullopt);
  EXPECT_EQ(literal_condition_value("1 2"), std::nullopt);
  EXPECT_EQ(literal_condition_value(""), std::nullopt);
  EXPECT_EQ(literal_condition_value(std::string(60, '(') + "1" + std::string(60, ')')), 1);
  EXPECT_EQ(literal_condition_value(std::string(100000, '(') + "1" + std::string(100000, ')')), std::nullopt);
  EXPECT_EQ(literal_condition_value(std::string(100000, '!') + "1"), std::nullopt);
}

// A stage with a uniform block gets WebGL's std140 default before the driver sees it; the
// driver's own errors after it still name the student's line.
TEST(WebglRulesTest, TheStd140DefaultMovesNoLine) {
  const std::string fragment =
      "#version 300 es\nprecision mediump float;\nuniform Light { vec4 tint; };\nout vec4 c;\n\n"
      "void main() { c = tint + undefined_name; }\n";
  const Diagnostic d = refusal("f.glsl", fragment);
  EXPECT_EQ(d.line, 6) << d.format();
  EXPECT_NE(d.message.find("undefined_name"), std::string::npos) << d.format();
}

// An extension the browser does not support, only enabled: its warning, and the driver does not
// get it either (the browser goes on without it).
TEST(WebglRulesTest, AnUnsupportedEnabledExtensionIsAWarningAndLeftOut) {
  const std::string fragment =
      "#version 300 es\n#extension GL_OES_standard_derivatives : enable\nprecision mediump float;\nout vec4 c;\n"
      "void main() { c = vec4(dFdx(1.0)); }\n";
  const auto r = compile_fragment("f.glsl", fragment);
  ASSERT_TRUE(r) << r.error().format();
  bool warned = false;
  for (const auto& d : r->diagnostics)
    warned |= d.severity == "warning" && d.line == 2 && d.message.find("extension is not supported") != std::string::npos;
  EXPECT_TRUE(warned);
}

// A link failure names its cause in the browser's words, found by ShadeLab before any driver
// (no driver log: a GPU's may name nothing).
TEST(WebglRulesTest, ALinkFailureNamesItsCause) {
  const std::string vertex = "#version 300 es\nout vec3 vNormal;\nvoid main() { vNormal = vec3(1.0); gl_Position = vec4(0.0); }\n";
  // A comment naming the input first: the cause is located at the declaration, not the comment.
  const std::string missing =
      "#version 300 es\n// vNorml: the normal\nprecision mediump float;\nin vec3 vNorml;\nout vec4 c;\nvoid main() { c = vec4(vNorml, 1.0); }\n";
  const std::string retyped = "#version 300 es\nprecision mediump float;\nin vec4 vNormal;\nout vec4 c;\nvoid main() { c = vNormal; }\n";
  auto r = testkit::shared_renderer().compile({"v.glsl", vertex}, {"f.glsl", missing});
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::link_failed);
  EXPECT_NE(r.error().message.find("FRAGMENT varying vNorml does not match any VERTEX varying"), std::string::npos)
      << r.error().message;
  EXPECT_TRUE(r.error().driver_log.empty()) << r.error().driver_log;
  EXPECT_EQ(r.error().diagnostics.front().line, 4);
  EXPECT_EQ(r.error().diagnostics.front().column, 9);
  r = testkit::shared_renderer().compile({"v.glsl", vertex}, {"f.glsl", retyped});
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::link_failed);
  EXPECT_NE(r.error().message.find("Types of varying 'vNormal' differ between VERTEX and FRAGMENT shaders: 3-component vector "
                                   "of float in the vertex shader, 4-component vector of float in the fragment shader"),
            std::string::npos) << r.error().message;
  EXPECT_EQ(r.error().diagnostics.front().line, 3);
}

// A pair the browser links and Mesa will not (a uniform of two precisions that only the
// fragment shader uses): accepted where the driver runs it, and where it does not, the server's
// limit (driver_refused, not the student's error), never a link_failed in the driver's words.
TEST(WebglRulesTest, WhatTheBrowserRunsIsNeverTheStudentsRefusal) {
  const auto r = testkit::shared_renderer().compile(
      {"v.glsl", "#version 300 es\nuniform highp vec4 u;\nvoid main() { gl_Position = vec4(0.0); }\n"},
      {"f.glsl", "#version 300 es\nprecision mediump float;\nuniform mediump vec4 u;\nout vec4 c;\nvoid main() { c = u; }\n"});
  if (over_a_driver_that_accepts_all()) {
    EXPECT_TRUE(r) << r.error().format();
    return;
  }
  if (r && !driver_is_mesa()) return;  // a GPU's driver that runs it, as the browser does
  ASSERT_FALSE(r);  // Debian 12's Mesa compares every uniform's precision
  EXPECT_EQ(r.error().code, ErrorCode::driver_refused) << r.error().format();
  EXPECT_FALSE(info(r.error().code).submission_caused);
  EXPECT_FALSE(r.error().driver_log.empty());  // for the staff and the operator
}

// The front end judges every stage, the driver none: a syntax error is refused by glslang, at its
// line, before any driver sees the source (a GPU driver may accept what the browser refuses).
TEST(WebglRulesTest, TheFrontEndRefusesBeforeTheDriver) {
  const auto r = compile_fragment("f.glsl", "#version 300 es\nprecision mediump float;\nout vec4 c;\nvoid main() { c = vec4(1.0) }\n");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::compile_failed);
  EXPECT_TRUE(r.error().driver_log.empty()) << r.error().driver_log;  // no driver judged it
  const Diagnostic* d = first_error(r.error());
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->line, 4);
  EXPECT_NE(d->message.find("syntax error"), std::string::npos) << d->format();
}

// The browser evaluates `#line 10 + 2`; the driver reads only numbers, and gets the number: its
// errors after the directive name the line they would after `#line 12`.
TEST(WebglRulesTest, ALineDirectiveWithAnExpressionGivesTheDriverItsNumber) {
  const auto after = [](const std::string& directive) {
    return refusal("f.glsl", "#version 300 es\n" + directive + "\nprecision mediump float;\nout vec4 c;\n" +
                                 std::string(20, '\n') + "void main() { c = undefined_name; }\n");
  };
  const Diagnostic evaluated = after("#define ONE 1\n#line ONE + 2"), plain = after("#define ONE 1\n#line 3");
  EXPECT_NE(evaluated.message.find("undefined_name"), std::string::npos) << evaluated.format();
  EXPECT_EQ(evaluated.line, plain.line) << evaluated.format() << " / " << plain.format();
  EXPECT_EQ(plain.line, 25);  // `#line 3` on line 3 numbers the next line 3: main, on line 26, is 25
}

// The preprocessor's output keeps each line in its place after a `#line`, so an extension below
// one is found on its own line (warned there, and only that line left out for the driver).
TEST(WebglRulesTest, DirectivesAfterALineDirectiveStayOnTheirLines) {
  const auto r = compile_fragment("f.glsl", "#version 300 es\n#line 100\n#extension GL_EXT_frag_depth : enable\n"
                                            "precision mediump float;\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n");
  ASSERT_TRUE(r) << r.error().format();
  ASSERT_EQ(r->diagnostics.size(), 1u);
  EXPECT_EQ(r->diagnostics[0].line, 3) << r->diagnostics[0].format();
  EXPECT_NE(r->diagnostics[0].message.find("'GL_EXT_frag_depth' : extension is not supported"), std::string::npos);
}

// Each language has its own reserved words: `sample` is reserved in GLSL ES 3.00, a free name in
// 1.00; the four image*Shadow names the browser reserves in both. Located at the word.
TEST(WebglRulesTest, ReservedWordsAreEachLanguagesOwn) {
  const auto es300 = [](const std::string& name) {
    return "#version 300 es\nprecision mediump float;\nout vec4 c;\nvoid main() { float " + name + " = 1.0; c = vec4(" + name + "); }\n";
  };
  const auto es100 = [](const std::string& name) {
    return "#version 100\nprecision mediump float;\nvoid main() { float " + name + " = 1.0; gl_FragColor = vec4(" + name + "); }\n";
  };
  for (const std::string name : {"image1DShadow", "image2DShadow", "image1DArrayShadow", "image2DArrayShadow"}) {
    for (const std::string& fragment : {es300(name), es100(name)}) {
      const auto r = testkit::shared_renderer().compile({"v.glsl", fragment.substr(0, fragment.find('\n') + 1) +
                                                                     "void main() { gl_Position = vec4(0.0); }\n"},
                                                        {"f.glsl", fragment});
      ASSERT_FALSE(r) << name;
      const Diagnostic& d = *first_error(r.error());
      EXPECT_NE(d.message.find("'" + name + "' : Illegal use of reserved word"), std::string::npos) << d.format();
      EXPECT_EQ(d.column, 21) << d.format();
    }
  }
  EXPECT_NE(refusal("f.glsl", es300("sample")).message.find("GLSL ES 3.00 section 3.8"), std::string::npos);
  const auto free_in_es100 = testkit::shared_renderer().compile(
      {"v.glsl", "#version 100\nvoid main() { gl_Position = vec4(0.0); }\n"}, {"f.glsl", es100("sample")});
  EXPECT_TRUE(free_in_es100) << free_in_es100.error().format();
}

// A malformed #extension is located at the token the browser quotes.
TEST(WebglRulesTest, AMalformedExtensionIsLocatedAtItsToken) {
  const Diagnostic d = refusal("f.glsl", "#version 300 es\n#extension GL_EXT_frag_depth : enable now\nprecision mediump float;\n"
                                         "out vec4 c;\nvoid main() { c = vec4(1.0); }\n");
  EXPECT_EQ(d.line, 2);
  EXPECT_EQ(d.column, 39) << d.format();
  EXPECT_NE(d.message.find("'now' : unexpected token"), std::string::npos) << d.format();
}
