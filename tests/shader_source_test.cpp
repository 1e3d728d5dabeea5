#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/files.h"

#include "shader/invariant_outputs.h"
#include "shader/uniform_variants.h"
#include "shader/shader_source.h"

using namespace shadelab;
using shader::Stage;

namespace {
Expected<shader::UnwrappedSource> unwrap(const std::string& text, Stage stage = Stage::fragment) {
  return shader::unwrap({"f.js", text}, stage);
}
constexpr const char* kBody = "#version 300 es\nprecision highp float;\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
}  // namespace

TEST(ShaderSourceTest, RawGlslPassesThroughWithIdentityLines) {
  auto s = unwrap(kBody);
  ASSERT_TRUE(s) << s.error().format();
  EXPECT_EQ(s->glsl, kBody);
  EXPECT_FALSE(s->from_js_module);
  EXPECT_EQ(s->locate(3, 5).file_line, 3);
  EXPECT_EQ(s->locate(3, 5).file_column, 5);
}

TEST(ShaderSourceTest, BacktickModuleUnwrapsAndMapsLinesToTheFile) {
  const std::string file = "// phong_frag.js\nexport default `" + std::string(kBody) + "`;\n";
  auto s = unwrap(file);
  ASSERT_TRUE(s) << s.error().format();
  EXPECT_TRUE(s->from_js_module);
  EXPECT_EQ(s->glsl, kBody);
  // GLSL line 1 starts after the back-tick on file line 2, column 17.
  EXPECT_EQ(s->locate(1, 1).file_line, 2);
  EXPECT_EQ(s->locate(1, 1).file_column, 17);
  EXPECT_EQ(s->locate(4, 3).file_line, 5);
  EXPECT_EQ(s->locate(4, 3).file_column, 3);
}

TEST(ShaderSourceTest, CrlfAndBomAreNormalised) {
  const std::string file = "\xEF\xBB\xBF" "export default `#version 300 es\r\nprecision highp float;\r\nout vec4 c;\r\nvoid main() { c = vec4(1.0); }\r\n`\r\n";
  auto s = unwrap(file);
  ASSERT_TRUE(s) << s.error().format();
  EXPECT_EQ(s->glsl, kBody);
}

TEST(ShaderSourceTest, QuotedStringsWithEscapesUnwrap) {
  auto s = unwrap("export default '#version 300 es\\nprecision highp float;\\nout vec4 c;\\nvoid main() { c = vec4(1.0); }\\n';");
  ASSERT_TRUE(s) << s.error().format();
  EXPECT_EQ(s->glsl, kBody);
  EXPECT_TRUE(s->warnings.empty());
}

TEST(ShaderSourceTest, QuotedStringAcrossLinesIsRefusedAtItsLine) {
  // The handout's own listing does this; a browser refuses the module, and so does ShadeLab,
  // saying how to write it.
  auto s = unwrap(std::string("export default '") + kBody + "'\n");
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().code, ErrorCode::shader_source_invalid);
  ASSERT_EQ(s.error().diagnostics.size(), 1u);
  EXPECT_EQ(s.error().diagnostics[0].line, 1);
  EXPECT_NE(s.error().message.find("back-ticks"), std::string::npos);
}

// The cases both readers of a module are held to (the page's, checked in Chromium beside the
// browser's own import(), in tests/browser/hostile.test.mjs): what the server reads of each file.
TEST(ShaderSourceTest, ModulesReadAsTheSharedCasesSay) {
  const auto doc = nlohmann::json::parse(testkit::read_text(testkit::source_dir() / "tests/shader_source/module_cases.json"));
  ASSERT_GE(doc["cases"].size(), 40u);
  for (const auto& c : doc["cases"]) {
    const std::string name = c["name"];
    auto s = unwrap(c["file"].get<std::string>());
    if (c.contains("glsl")) {
      ASSERT_TRUE(s) << name << ": " << s.error().format();
      EXPECT_EQ(s->glsl, c["glsl"].get<std::string>()) << name;
      continue;
    }
    ASSERT_FALSE(s) << name << ": read as " << s->glsl;
    if (c["refused"].is_string()) {
      EXPECT_NE(s.error().message.find(c["refused"].get<std::string>()), std::string::npos) << name << ": " << s.error().message;
    }
  }
}

TEST(ShaderSourceTest, TemplateEscapesAndLineContinuationsFollowJavaScript) {
  auto s = unwrap("export default `#version 300 es\n// a \\` tick and \\\\ slash\n#define A 1 \\\n+ 2\n`");
  ASSERT_TRUE(s) << s.error().format();
  EXPECT_EQ(s->glsl, "#version 300 es\n// a ` tick and \\ slash\n#define A 1 + 2\n");
}

TEST(ShaderSourceTest, InterpolationIsAnErrorAtItsLine) {
  auto s = unwrap("export default `#version 300 es\nfloat x = ${value};\n`");
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().code, ErrorCode::shader_source_invalid);
  ASSERT_EQ(s.error().diagnostics.size(), 1u);
  EXPECT_EQ(s.error().diagnostics[0].line, 2);
  EXPECT_EQ(s.error().diagnostics[0].column, 11);
}

TEST(ShaderSourceTest, UnclosedStringPointsAtItsOpening) {
  auto s = unwrap("\nexport default `#version 300 es\nvoid main() {}\n");
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().diagnostics[0].line, 2);
  EXPECT_EQ(s.error().diagnostics[0].column, 16);
}

TEST(ShaderSourceTest, TextAfterTheStringIsAnError) {
  auto s = unwrap("export default `" + std::string(kBody) + "`;\nconsole.log('hi');\n");
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().code, ErrorCode::shader_source_invalid);
  EXPECT_EQ(s.error().diagnostics[0].line, 6);  // the back-tick closes on line 5
}

// WebGL 2 compiles GLSL ES 1.00 too: a shader with no #version is one, as is `#version 100`.
TEST(ShaderSourceTest, NoVersionOrVersion100IsGlslEs100) {
  for (const char* text : {"precision highp float;\nvoid main() {}\n", "#version 100\nvoid main() {}\n", "  #version 100  \r\nvoid main() {}\n"}) {
    auto s = unwrap(text);
    ASSERT_TRUE(s) << text << ": " << s.error().format();
    EXPECT_EQ(s->version, shader::GlslVersion::es100) << text;
  }
  auto es300 = unwrap("#version 300 es\nvoid main() {}\n");
  ASSERT_TRUE(es300);
  EXPECT_EQ(es300->version, shader::GlslVersion::es300);
}

TEST(ShaderSourceTest, ShadersOfTwoVersionsDoNotLinkAndSaySo) {
  const shader::ShaderFile vf{"phong_vert.js", "#version 300 es\nvoid main() {}\n"}, ff{"phong_frag.js", "void main() {}\n"};
  auto vs = shader::unwrap(vf, Stage::vertex), fs = shader::unwrap(ff, Stage::fragment);
  ASSERT_TRUE(vs && fs);
  auto linked = shader::check_same_version(*vs, *fs, ff);
  ASSERT_FALSE(linked);
  EXPECT_EQ(linked.error().code, ErrorCode::link_failed);
  EXPECT_EQ(linked.error().message, "the vertex shader is GLSL ES 3.00 and the fragment shader GLSL ES 1.00: a program links shaders "
                                    "of one version (both `#version 300 es`, or both GLSL ES 1.00)");
  EXPECT_EQ(linked.error().diagnostics.at(0).file, "phong_frag.js");
  EXPECT_TRUE(shader::check_same_version(*vs, *vs, vf));
}

TEST(ShaderSourceTest, VersionNotOnTheFirstLineIsAnErrorAtThatLine) {
  // A newline straight after the back-tick: the mistake WebGL2 reports as "must occur on the first line".
  auto s = unwrap("export default `\n#version 300 es\nvoid main() {}\n`");
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().code, ErrorCode::missing_version);
  EXPECT_EQ(s.error().diagnostics[0].line, 2);
  EXPECT_NE(s.error().message.find("first line"), std::string::npos);
}

TEST(ShaderSourceTest, AVersionWebGl2DoesNotCompileIsAnError) {
  for (const char* text : {"#version 310 es\nvoid main() {}\n", "#version 300\nvoid main() {}\n", "#version 330 core\nvoid main() {}\n"}) {
    auto s = unwrap(text);
    ASSERT_FALSE(s) << text;
    EXPECT_EQ(s.error().code, ErrorCode::missing_version) << text;
    EXPECT_NE(s.error().message.find("`#version 300 es` (GLSL ES 3.00) or `#version 100`"), std::string::npos) << s.error().message;
  }
}

TEST(ShaderSourceTest, EmptyNulInvalidUtf8AndOversizedSourcesAreErrors) {
  EXPECT_EQ(unwrap("").error().code, ErrorCode::shader_source_invalid);
  EXPECT_EQ(unwrap("  \n\t\n").error().code, ErrorCode::shader_source_invalid);
  EXPECT_EQ(unwrap(std::string("#version 300 es\nvoid main() {}\0", 32)).error().code, ErrorCode::shader_source_invalid);
  auto bad_utf8 = unwrap("#version 300 es\n// caf\xC3\n");
  ASSERT_FALSE(bad_utf8);
  EXPECT_EQ(bad_utf8.error().diagnostics[0].line, 2);
  const std::string huge = "#version 300 es\n" + std::string(1 << 20, ' ');
  auto big = unwrap(huge);
  ASSERT_FALSE(big);
  EXPECT_NE(big.error().message.find("limit"), std::string::npos);
}

TEST(ShaderSourceTest, Utf8InCommentsIsFine) {
  auto s = unwrap("#version 300 es\n// café — ünïcode\nvoid main() {}\n");
  EXPECT_TRUE(s) << s.error().format();
}

// The float check's outputs (shader/invariant_outputs.h): each global output redeclared invariant
// on its own line, nothing else touched.
TEST(InvariantOutputsTest, EveryGlobalOutputAndNothingElse) {
  using shader::Stage;
  using shader::with_invariant_outputs;
  EXPECT_EQ(with_invariant_outputs("#version 300 es\nout vec4 fragColor;\nvoid main() {}\n", Stage::fragment),
            "#version 300 es\nout vec4 fragColor; invariant fragColor;\nvoid main() {}\n");
  EXPECT_EQ(with_invariant_outputs("layout(location = 0) out highp vec4 c;", Stage::fragment),
            "layout(location = 0) out highp vec4 c; invariant c;");
  EXPECT_EQ(with_invariant_outputs("in vec4 p;\nout vec4 a[2], b;\nout vec3 n;", Stage::vertex),
            "in vec4 p;\nout vec4 a[2], b; invariant a, b, gl_Position;\nout vec3 n; invariant n;");
  for (const std::string untouched :
       {"void f(out vec3 x);\nvoid f(out vec3 x) { x = vec3(0); }", "void main() { vec4 out_ = vec4(0); }",
        "// out vec4 c;\n/* out vec4 d; */\n#define X out\n", "invariant out vec4 c;", "uniform vec4 outside;"})
    EXPECT_EQ(with_invariant_outputs(untouched, Stage::fragment), untouched);
}

// One pass for every light (shader/uniform_variants.h): the student's lines where they were, main
// renamed, the light a plain global set from an array a run at a time, and what one pass cannot
// give declined with the reason.
namespace {

shader::UnwrappedSource es300(const std::string& glsl, Stage stage) {
  auto s = shader::unwrap({"shader.glsl", glsl}, stage);
  EXPECT_TRUE(s) << s.error().format();
  return s ? *s : shader::UnwrappedSource{};
}

const std::string kVertex = "#version 300 es\nin vec4 p;\nout vec3 v;\nvoid main() { v = p.xyz; gl_Position = p; }\n";

Expected<std::string> variants(const std::string& fragment, int runs = 2) {
  return shader::with_uniform_variants(es300(kVertex, Stage::vertex), es300(fragment, Stage::fragment), {"uLight"}, runs, 8);
}

}  // namespace

TEST(UniformVariantsTest, TheStudentsLinesStayAndMainRunsOncePerValue) {
  const std::string fragment =
      "#version 300 es\nprecision highp float;\nuniform highp vec3 uLight;\nin vec3 v;\n"
      "layout(location = 0) out vec4 fragColor;\nvoid main(void) {\n  fragColor = vec4(uLight * v, 1.0);\n}\n";
  auto out = variants(fragment);
  ASSERT_TRUE(out) << out.error().message;
  const std::string head = out->substr(0, out->find("\n// One pass"));
  EXPECT_EQ(std::count(head.begin(), head.end(), '\n'), std::count(fragment.begin(), fragment.end(), '\n'));
  EXPECT_NE(head.find("        highp vec3 uLight;"), std::string::npos) << head;
  EXPECT_NE(head.find("                        vec4 fragColor;"), std::string::npos) << head;
  EXPECT_NE(head.find("void shadelab_run(void)"), std::string::npos) << head;
  EXPECT_NE(out->find("uniform highp vec3 shadelab_variant_uLight[2];"), std::string::npos) << *out;
  EXPECT_NE(out->find("layout(location = 1) out highp vec4 shadelab_output_1;"), std::string::npos) << *out;
  EXPECT_NE(out->find("uLight = shadelab_variant_uLight[shadelab_k];"), std::string::npos) << *out;
}

TEST(UniformVariantsTest, WhatOnePassCannotGiveIsDeclinedWithTheReason) {
  const auto declined = [](const Expected<std::string>& r, const std::string& why) {
    EXPECT_FALSE(r) << why;
    if (!r) {
      EXPECT_NE(r.error().message.find(why), std::string::npos) << r.error().message;
    }
  };
  const std::string head = "#version 300 es\nprecision highp float;\nuniform vec3 uLight;\nin vec3 v;\nout vec4 c;\n";
  declined(variants(head + "void main() { if (v.x > 0.5) discard; c = vec4(uLight, 1); }"), "discard");
  declined(variants(head + "void main() { gl_FragDepth = 0.5; c = vec4(uLight, 1); }"), "gl_FragDepth");
  declined(variants(head + "vec3 lit;\nvoid main() { lit += uLight; c = vec4(lit, 1); }"), "the global lit");
  declined(variants(head + "out vec4 d;\nvoid main() { c = vec4(uLight, 1); d = c; }"), "more than one vec4 output");
  declined(variants("#version 300 es\nprecision highp float;\nuniform vec3 a, uLight;\nout vec4 c;\nvoid main() { c = vec4(uLight + a, 1); }"),
           "not declared as a plain vec3 or vec4 uniform");
  declined(variants("#version 300 es\nprecision highp float;\nuniform mat3 uLight;\nout vec4 c;\nvoid main() { c = vec4(uLight[0], 1); }"),
           "not declared as a plain vec3 or vec4 uniform");
  declined(variants(head + "void main() { c = vec4(uLight, 1); }", 9), "9 runs need 9 outputs, 8 are drawn at once");
  declined(shader::with_uniform_variants(es300(kVertex, Stage::vertex), es300("#version 100\nprecision highp float;\nuniform vec3 uLight;\n"
                                                                                 "void main() { gl_FragColor = vec4(uLight, 1); }", Stage::fragment),
                                         {"uLight"}, 2, 8),
           "GLSL ES 1.00");
  auto gouraud = kVertex;
  gouraud.replace(gouraud.find("in vec4 p;"), 10, "in vec4 p; uniform vec3 uLight;");
  declined(shader::with_uniform_variants(es300(gouraud, Stage::vertex), es300(head + "void main() { c = vec4(v, 1); }", Stage::fragment),
                                         {"uLight"}, 2, 8),
           "the vertex shader uses uLight");
  EXPECT_TRUE(variants(head + "const float k = 2.0;\nfloat lit(vec3 l) { return k * l.x; }\nvoid main() { c = vec4(lit(uLight)); }"));
}

// The census (each run's NaN and infinity flags, two runs an output) after the runs' colours; one
// run alone has nobody to share a decision or a global with.
TEST(UniformVariantsTest, TheCensusFollowsTheColoursTwoRunsAnOutput) {
  const std::string head = "#version 300 es\nprecision highp float;\nuniform vec3 uLight;\nin vec3 v;\nout vec4 c;\n";
  const auto census = [&](const std::string& body, int runs, std::vector<std::string> names) {
    return shader::with_uniform_variants(es300(kVertex, Stage::vertex), es300(head + body, Stage::fragment), names, runs, 8, true);
  };
  auto three = census("void main() { c = vec4(uLight, 1); }", 3, {"uLight"});
  ASSERT_TRUE(three) << three.error().message;
  EXPECT_NE(three->find("layout(location = 3) out highp vec4 shadelab_census_0;"), std::string::npos) << *three;
  EXPECT_NE(three->find("layout(location = 4) out highp vec4 shadelab_census_1;"), std::string::npos) << *three;
  EXPECT_NE(three->find("shadelab_census_1 = vec4(shadelab_non_finite(shadelab_colour[2]), vec2(0.0));"), std::string::npos) << *three;
  EXPECT_EQ(three->find("if ("), std::string::npos) << "no branch on the colour: " << *three;
  EXPECT_EQ(three->find('?'), std::string::npos) << "no branch on the colour: " << *three;
  EXPECT_EQ(shader::variant_outputs(5, true).total(), 8);
  EXPECT_FALSE(census("void main() { c = vec4(uLight, 1); }", 6, {"uLight"}));
  const std::string alone[] = {"void main() { if (v.x > 0.5) discard; c = vec4(uLight, 1); }",
                               "vec3 lit;\nvoid main() { lit += uLight; c = vec4(lit, 1); }"};
  for (const auto& body : alone) {
    EXPECT_TRUE(census(body, 1, {})) << body;
    EXPECT_FALSE(census(body, 2, {"uLight"})) << body;
  }
  // A macro would reach the grader's code: this one would hide every NaN from the census.
  const auto blinded = census("#define floatBitsToUint(x) uvec4(0u)\nvoid main() { c = vec4(uLight, 1); }", 1, {});
  ASSERT_FALSE(blinded);
  EXPECT_NE(blinded.error().message.find("macro"), std::string::npos) << blinded.error().message;
  EXPECT_TRUE(census("#ifdef GL_ES\nvoid main() { c = vec4(uLight, 1); }\n#endif\n", 1, {})) << "only a #define declines";
}
