// The values a student's fragment stage computes, read at the grade's pixels beside the
// reference's (issue 79): probing keeps every line where it is, each probe draws the value of its
// own write on the real driver, and the lines where a value first departs from its counterpart's
// are the lines each mistake was made at, in the real student's shape of program (`coeffDiffuse`,
// `R = -reflect(L, N)`, `+=` accumulation), written here.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "course/course_reader.h"
#include "grade/value_reading.h"
#include "repair/repair_candidates.h"
#include "repair/value_probes.h"
#include "shader/glsl_lines.h"
#include "support/run_command.h"
#include "support/test_support.h"
#include "support/tutorial_program.h"

namespace shadelab {
namespace {

const course::Preset& specular() { return *course::builtin_course().preset("specular"); }

std::string reference_glsl() { return shader::unwrap(specular().fragment, shader::Stage::fragment)->glsl; }

// The reference's declarations with `body` as main.
std::string student_with(const std::string& body) {
  const std::string reference = reference_glsl();
  return reference.substr(0, reference.find("void main(void) {")) + body;
}

const char* kStudentShape =
    "void main(void) {\n"
    "    float specularAlpha = 6.0;\n"
    "    vec3 N = normalize(vNormal);\n"
    "    vec3 L = normalize(uLightPosition - vPosition);\n"
    "    vec3 V = normalize(-vPosition);\n"
    "    vec3 R = -reflect(L, N);\n"
    "    float coeffDiffuse = max(dot(N, L), 0.0);\n"
    "    float coeffSpecular = 0.0;\n"
    "    if (coeffDiffuse > 0.0) {\n"
    "        coeffSpecular = pow(max(dot(R, V), 0.0), specularAlpha);\n"
    "    }\n"
    "    fragColor = uAmbientColor;\n"
    "    fragColor += coeffDiffuse * uDiffuseColor * uLightColor;\n"
    "    fragColor += coeffSpecular * uSpecularColor * uLightColor;\n"
    "}\n";

std::string typed(std::string text, const std::string& find, const std::string& with) {
  const auto at = text.find(find);
  EXPECT_NE(at, std::string::npos) << find;
  if (at != std::string::npos) text.replace(at, find.size(), with);
  return text;
}

int line_of(const std::string& glsl, const std::string& text) {
  const auto lines = shader::lines_of(glsl);
  for (size_t i = 0; i < lines.size(); ++i)
    if (lines[i].find(text) != std::string_view::npos) return static_cast<int>(i) + 1;
  ADD_FAILURE() << text;
  return 0;
}

const repair::ValueProbe* probe(const repair::ProbedStage& s, const std::string& name, int ordinal) {
  for (const auto& p : s.probes)
    if (!p.input && p.name == name && p.ordinal == ordinal) return &p;
  return nullptr;
}

TEST(ValueProbesTest, EachWriteOfMainIsProbedOnItsOwnLine) {
  const std::string glsl = student_with(kStudentShape);
  const auto probed = repair::probed_fragment(glsl);
  ASSERT_TRUE(probed);
  EXPECT_EQ(shader::lines_of(probed->glsl).size(), shader::lines_of(glsl).size()) << "no line moves";
  ASSERT_GE(probed->probes.size(), 2u);
  EXPECT_TRUE(probed->probes[0].input && probed->probes[1].input) << "the inputs first, as main receives them";

  const auto* diffuse = probe(*probed, "coeffDiffuse", 0);
  ASSERT_NE(diffuse, nullptr);
  EXPECT_EQ(diffuse->line, line_of(glsl, "float coeffDiffuse"));
  EXPECT_EQ(diffuse->reads, (std::vector<std::string>{"N", "L"}));
  const auto* guarded = probe(*probed, "coeffSpecular", 1);
  ASSERT_NE(guarded, nullptr) << "a write inside braces is probed";
  EXPECT_TRUE(guarded->last);
  EXPECT_FALSE(probe(*probed, "coeffSpecular", 0)->last);
  // The output's writes: the first `=`, then two `+=` that read what it held.
  const auto* third = probe(*probed, "fragColor", 2);
  ASSERT_NE(third, nullptr);
  EXPECT_TRUE(third->last);
  EXPECT_EQ(third->reads, (std::vector<std::string>{"fragColor", "coeffSpecular"}));
  EXPECT_TRUE(probe(*probed, "fragColor", 0)->reads.empty()) << "a uniform is the page's, not a value to align";

  // An `if` without braces: its write is not probed (a probe after it would run unguarded).
  const auto unbraced = repair::probed_fragment(typed(glsl, "if (coeffDiffuse > 0.0) {\n        coeffSpecular = pow(max(dot(R, V), 0.0), specularAlpha);\n    }",
                                                      "if (coeffDiffuse > 0.0) coeffSpecular = pow(max(dot(R, V), 0.0), specularAlpha);"));
  ASSERT_TRUE(unbraced);
  EXPECT_EQ(probe(*unbraced, "coeffSpecular", 1), nullptr);

  // What cannot be probed is not: GLSL ES 1.00, two outputs.
  EXPECT_FALSE(repair::probed_fragment(typed(glsl, "#version 300 es", "")));
  EXPECT_FALSE(repair::probed_fragment(typed(glsl, "out vec4 fragColor;", "out vec4 fragColor;\nout vec4 other;")));
  // A hostile name: a local of the probes' own prefix would shadow their output; the stage is not probed.
  EXPECT_FALSE(repair::probed_fragment(typed(glsl, "float coeffSpecular = 0.0;", "vec4 valueprobe_out = vec4(1.0); float coeffSpecular = 0.0;")));
}

// The probes draw what main computes: the reference's values each agree with themselves, and the
// student's with their counterparts up to the line a mistake is made at.
grade::ValueCanvas small() { return {32, 2}; }

// Read under the page's light and, as the grade reads a program its orange probe light fails,
// under an orange one: a value that leaves out the light's colour differs only there.
repair::ValueAgreement values_of(const std::string& fragment) {
  render::RenderRequest reference = testkit::preset_request("specular"), orange = reference;
  orange.uniforms.push_back({"uLightColor", {1.0, 0.5, 0.2, 1.0}});
  std::vector<render::RenderRequest> student = {reference, orange};
  for (auto& r : student) r.fragment = {"student.frag", fragment};
  return grade::read_values(testkit::shared_renderer(), student, {reference, orange}, testkit::builtin("bunny"), small());
}

TEST(ValueProbesTest, EachProbeDrawsItsOwnValue) {
  const auto same = values_of(reference_glsl());
  ASSERT_TRUE(same.read);
  for (size_t i = 0; i < same.agrees_with.size(); ++i) {
    EXPECT_TRUE(same.compared[i]) << i;
    EXPECT_NE(std::find(same.agrees_with[i].begin(), same.agrees_with[i].end(), static_cast<int>(i)), same.agrees_with[i].end()) << i;
  }
  // A stage of more writes than the budget of probes is not drawn at all (each probe is a run of main).
  std::string many = "void main(void) {\n    float x = 0.0;\n";
  for (int k = 0; k < 70; ++k) many += "    x += 0.001;\n";
  many += "    fragColor = vec4(x);\n}\n";
  EXPECT_FALSE(values_of(student_with(many)).read);
  // A value the reference never computes agrees with nothing.
  const auto doubled = values_of(typed(reference_glsl(), "fragColor = color;", "fragColor = 2.0 * color;"));
  ASSERT_TRUE(doubled.read);
  EXPECT_TRUE(doubled.agrees_with.back().empty());
}

std::set<int> departing(const std::string& fragment) {
  const shader::ShaderFile file{"student.frag", fragment};
  const auto program = repair::repair_program(specular().vertex, file, specular().vertex, specular().fragment, {});
  EXPECT_TRUE(program.ok());
  return program ? repair::lines_of(repair::departures(program->read, values_of(fragment))) : std::set<int>{};
}

TEST(ValueProbesTest, AValueDepartsAtTheLineItsMistakeIsMadeAt) {
  const std::string right = student_with(kStudentShape);
  EXPECT_TRUE(departing(right).empty()) << "nothing departs in a right program";

  // L not normalised: L departs (what it reads is right), and R, N.L and the colour do not, as
  // they read the wrong L.
  const std::string unnormalised = typed(right, "normalize(uLightPosition - vPosition)", "uLightPosition - vPosition");
  EXPECT_EQ(departing(unnormalised), (std::set<int>{line_of(right, "vec3 L =")}));

  // Two mistakes whose values do not depend on each other: each departs at its own line.
  const std::string pair = typed(unnormalised, "float specularAlpha = 6.0;", "float specularAlpha = 16.0;");
  EXPECT_EQ(departing(pair), (std::set<int>{line_of(right, "float specularAlpha"), line_of(right, "vec3 L =")}));

  // A wrong normal departs at N's line, whatever reads it after.
  EXPECT_EQ(departing(typed(right, "normalize(vNormal)", "normalize(vNormal + vec3(0.5))")), (std::set<int>{line_of(right, "vec3 N =")}));
}

// What turns one value into another, read off the two at every pixel on the CPU: each change of
// repair/value_change.h found where it holds, and nothing claimed where no one change does.
TEST(ValueProbesTest, AChangeBetweenTwoValuesIsReadOffTheirPixels) {
  using repair::ValueChange;
  std::vector<std::array<float, 3>> values;
  for (int i = 0; i < 40; ++i) {
    const float a = static_cast<float>(i) / 39.0f;
    values.push_back({0.9f * a - 0.3f, 0.2f + 0.5f * a * a, 0.7f - 0.6f * a});  // some below 0, none the others' order
  }
  const auto changes = [&](auto f) {
    std::vector<repair::ValueSample> samples;
    for (const auto& v : values) samples.push_back({v, f(v)});
    return repair::changes_between(samples);
  };
  using V = std::array<float, 3>;
  const auto has = [](const std::vector<ValueChange>& c, ValueChange k) { return std::find(c.begin(), c.end(), k) != c.end(); };
  EXPECT_TRUE(changes([](V v) { return v; }).empty()) << "the same values need no change";
  EXPECT_EQ(changes([](V v) { return V{-v[0], -v[1], -v[2]}; }), std::vector<ValueChange>{ValueChange::negated});
  const auto normalised = changes([](V v) {
    const float n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return V{v[0] / n, v[1] / n, v[2] / n};
  });
  EXPECT_EQ(normalised, std::vector<ValueChange>{ValueChange::normalised});
  const auto longer = [&] {
    std::vector<repair::ValueSample> samples;
    for (const auto& v : values) {
      const float n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      samples.push_back({V{v[0] / n, v[1] / n, v[2] / n}, V{v[0] * 3, v[1] * 3, v[2] * 3}});
    }
    return repair::changes_between(samples);
  }();
  EXPECT_TRUE(has(longer, ValueChange::unnormalised)) << "the student normalised what the homework keeps at its length";
  EXPECT_EQ(changes([](V v) { return V{std::max(v[0], 0.f), std::max(v[1], 0.f), std::max(v[2], 0.f)}; }),
            std::vector<ValueChange>{ValueChange::clamped});
  EXPECT_EQ(changes([](V v) { return V{v[0] * 1.0f, v[1] * 0.5f, v[2] * 0.2f}; }), std::vector<ValueChange>{ValueChange::scaled})
      << "the orange light's colour left out";
  EXPECT_EQ(changes([](V v) { return V{v[0] + 0.1f, v[1] + 0.1f, v[2] + 0.1f}; }), std::vector<ValueChange>{ValueChange::shifted})
      << "the ambient term left out";
  EXPECT_EQ(changes([](V v) { return V{v[2], v[1], v[0]}; }), std::vector<ValueChange>{ValueChange::swizzled});
  // A cosine (0 to 1) to the homework's power, and to another power.
  std::vector<repair::ValueSample> cosines;
  for (int i = 1; i < 40; ++i) {
    const float c = static_cast<float>(i) / 40.0f;
    cosines.push_back({{c, c, c}, {std::pow(c, 6.0f), std::pow(c, 6.0f), std::pow(c, 6.0f)}});
  }
  EXPECT_TRUE(has(repair::changes_between(cosines), ValueChange::powered));
  // A value that no one change makes: nothing is claimed.
  EXPECT_TRUE(changes([](V v) { return V{v[0] * v[0] + 0.3f, v[2], -v[1] * 2}; }).empty());
  EXPECT_TRUE(repair::changes_between({}).empty()) << "no pixel: nothing known";
}

// At a line where a value departs, the change its value needs, read on the real driver: R's and
// V's signs (negated), L's normalisation, the exponent's number. (A clamp or an exponent left out
// of a local the reference has no counterpart of departs nowhere: the CPU test above reads those.)
TEST(ValueProbesTest, EachDepartureSaysTheChangeItsValueNeeds) {
  using repair::ValueChange;
  const std::string right = student_with(kStudentShape);
  const auto at = [&](const std::string& fragment, const std::string& line) {
    const shader::ShaderFile file{"student.frag", fragment};
    const auto program = repair::repair_program(specular().vertex, file, specular().vertex, specular().fragment, {});
    EXPECT_TRUE(program.ok());
    const auto d = program ? repair::departures(program->read, values_of(fragment)) : repair::Departures{};
    const auto it = d.find(line_of(right, line));
    EXPECT_NE(it, d.end()) << line << ": departs at " << ::testing::PrintToString(repair::lines_of(d));
    return it == d.end() ? std::set<ValueChange>{} : it->second;
  };
  EXPECT_EQ(at(typed(right, "vec3 R = -reflect(L, N);", "vec3 R = reflect(L, N);"), "vec3 R ="), std::set<ValueChange>{ValueChange::negated});
  EXPECT_TRUE(at(typed(right, "normalize(uLightPosition - vPosition)", "uLightPosition - vPosition"), "vec3 L =").count(ValueChange::normalised));
  EXPECT_EQ(at(typed(right, "normalize(-vPosition)", "normalize(vPosition)"), "vec3 V ="), std::set<ValueChange>{ValueChange::negated});
  EXPECT_TRUE(at(typed(right, "float specularAlpha = 6.0;", "float specularAlpha = 16.0;"), "float specularAlpha").count(ValueChange::scaled))
      << "a number times another";
  EXPECT_EQ(at(typed(right, "vec3 V = normalize(-vPosition);", "vec3 V = L;"), "vec3 V ="), std::set<ValueChange>{ValueChange::replaced})
      << "no one change of V's, but another of the reference's values: only V put back makes it";
}

// A mistake whose value every later value reads hides a second one from the values: with L not
// normalised, R with the wrong sign reads a wrong L and departs nowhere. Once L is normalised (the
// single that draws nearest), R departs at its own line, and a line an edit puts in moves the
// student's lines after it by one.
TEST(ValueProbesTest, ASecondMistakeDepartsOnceTheFirstIsMended) {
  const std::string right = student_with(kStudentShape);
  const std::string sign = typed(right, "vec3 R = -reflect(L, N);", "vec3 R = reflect(L, N);");
  const std::string pair = typed(sign, "normalize(uLightPosition - vPosition)", "uLightPosition - vPosition");
  const int l_line = line_of(right, "vec3 L ="), r_line = line_of(right, "vec3 R =");
  EXPECT_EQ(departing(pair), (std::set<int>{l_line})) << "the second mistake is hidden";
  const shader::ShaderFile file{"student.frag", pair};
  const auto program = repair::repair_program(specular().vertex, file, specular().vertex, specular().fragment, {});
  ASSERT_TRUE(program.ok());
  const auto singles = repair::single_candidates(*program, {.own = 200, .reference = 200});
  const auto normalised = std::find_if(singles.begin(), singles.end(), [&](const auto& c) { return c.fragment.text == sign; });
  ASSERT_NE(normalised, singles.end()) << "a single normalises L";
  EXPECT_EQ(repair::lines_of(repair::departing_after(*program, *normalised, values_of(sign))), (std::set<int>{r_line}));
  // An edit that puts in a line of its own before the second mistake's (of the program with L
  // right): the lines it says are the student's.
  const shader::ShaderFile sign_file{"student.frag", sign};  // the reading keeps its address
  const auto alone = repair::repair_program(specular().vertex, sign_file, specular().vertex, specular().fragment, {});
  ASSERT_TRUE(alone.ok());
  repair::RepairEdit e = normalised->edits.front();
  e.begin = e.end = sign.find("    vec3 V =");
  e.line = line_of(sign, "vec3 V =");
  e.with = "    float unread = 1.0;\n";
  const auto inserted = repair::candidate_of(*alone, {e});
  ASSERT_EQ(inserted.fragment.text, sign.substr(0, e.begin) + e.with + sign.substr(e.begin));
  EXPECT_EQ(repair::lines_of(repair::departing_after(*alone, inserted, values_of(inserted.fragment.text))), (std::set<int>{r_line}));
}

// The colour summed into the output term by term: a term that leaves out the light's colour
// departs at its own line (the output before it holds the reference's ambient and diffuse sum,
// after it what the reference outputs), under the orange light only.
TEST(ValueProbesTest, ATermSummedIntoTheOutputDepartsAtItsLine) {
  const std::string right = student_with(
      "void main(void) {\n"
      "    vec3 N = normalize(vNormal);\n"
      "    vec3 L = normalize(uLightPosition - vPosition);\n"
      "    vec3 V = normalize(-vPosition);\n"
      "    vec3 R = reflect(-L, N);\n"
      "    float lambert = max(dot(N, L), 0.0);\n"
      "    fragColor = uAmbientColor;\n"
      "    fragColor += uDiffuseColor * uLightColor * lambert;\n"
      "    if (lambert > 0.0) {\n"
      "        fragColor += uSpecularColor * uLightColor * pow(max(dot(R, V), 0.0), 6.0);\n"
      "    }\n"
      "}\n");
  EXPECT_TRUE(departing(right).empty());
  const std::string colour = typed(right, "uSpecularColor * uLightColor * pow", "uSpecularColor * pow");
  EXPECT_EQ(departing(colour), (std::set<int>{line_of(right, "uSpecularColor * uLightColor")}));
}

// Through the grade (`shadelab grade`, the CLI a TA runs): the repair search's report.
nlohmann::json searched(const std::string& fragment) {
  const auto dir = std::filesystem::temp_directory_path() / ("value_probes_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "phong.vert") << shader::unwrap(specular().vertex, shader::Stage::vertex)->glsl;
  std::ofstream(dir / "phong.frag") << fragment;
  const auto run = testkit::run_shadelab("grade --vert " + (dir / "phong.vert").string() + " --frag " + (dir / "phong.frag").string() +
                                         " --reference specular --cache-dir " + (dir / "store").string());
  std::filesystem::remove_all(dir);
  const auto json = nlohmann::json::parse(run.output.substr(run.output.find('{'), run.output.rfind('}') - run.output.find('{') + 1));
  return json.at("repairSearch");
}

std::set<int> lines_of(const nlohmann::json& search) {
  if (!search.contains("found") || !search.contains("also")) return {};
  return {search["found"]["line"].get<int>(), search["also"]["line"].get<int>()};
}

// A pair whose values depart at both lines is repaired at both, its two lines' singles screened
// before any other single (there are 81), those that make the change each line's value needs
// (L normalised, a number refitted) first and paired before the others (18 candidates before the
// changes were read, 4 now); a pair whose second mistake the first hides is repaired from the
// nearest chosen single's values (79 candidates before they were read, 16 before the chosen
// single's were read before the other singles, 2 now).
TEST(ValueProbesTest, APairIsRepairedFromTheLinesWhereItsValuesDepart) {
  const std::string right = student_with(kStudentShape);
  const std::string unnormalised = typed(right, "normalize(uLightPosition - vPosition)", "uLightPosition - vPosition");
  const auto both = searched(typed(unnormalised, "float specularAlpha = 6.0;", "float specularAlpha = 16.0;"));
  EXPECT_EQ(lines_of(both), (std::set<int>{line_of(right, "float specularAlpha"), line_of(right, "vec3 L =")})) << both.dump();
  EXPECT_LE(both["candidates"].get<int>(), 6) << "the two lines' chosen singles, then their pairs: not every single first";
  const auto hidden = searched(typed(unnormalised, "vec3 R = -reflect(L, N);", "vec3 R = reflect(L, N);"));
  EXPECT_EQ(lines_of(hidden), (std::set<int>{line_of(right, "vec3 R ="), line_of(right, "vec3 L =")})) << hidden.dump();
  EXPECT_LE(hidden["candidates"].get<int>(), 6) << "L normalised, then paired with R's line's sign: not every single first";
  EXPECT_EQ(hidden.value("valuesRead", 0), 1) << "the nearest single's values, read once";
  EXPECT_FALSE(both.contains("valuesRead")) << "both lines departed: no single's values needed";
}

// A tutorial's names (`viewDir`, `reflectDir`), with both lines that declare them changed: V from
// the eye, or computed as L, beside the half vector where the homework reflects. Neither
// declaration reads as the reference's, so the names align by their use (`dot(viewDir,
// reflectDir)` as `dot(V, R)`); then V departs with the change it needs (a sign; another of the
// reference's values), and the chosen single's own values show R departing, whose value is put
// back: both lines within a few candidates (2 and 7), where the search spent its whole budget (140
// and 150 candidates) and found none.
TEST(ValueProbesTest, APairThatChangesBothNamedLinesIsRepairedAtBoth) {
  const std::string right = student_with(testkit::kTutorialSpecularMain);
  const std::string half = typed(right, "reflect(-lightDir, norm)", "normalize(lightDir + viewDir)");
  const std::set<int> both{line_of(right, "vec3 viewDir ="), line_of(right, "vec3 reflectDir =")};
  const auto from_eye = searched(typed(half, "normalize(-vPosition)", "normalize(vPosition)"));
  EXPECT_EQ(lines_of(from_eye), both) << from_eye.dump();
  EXPECT_LE(from_eye["candidates"].get<int>(), 4) << "V's sign chosen, then R put back beside it";
  const auto as_light = searched(typed(half, "vec3 viewDir = normalize(-vPosition);", "vec3 viewDir = lightDir;"));
  EXPECT_EQ(lines_of(as_light), both) << as_light.dump();
  EXPECT_LE(as_light["candidates"].get<int>(), 8) << "V's name replaced (the student's own edit, tried first) or V put back, then R beside it";
  // The names aligned by their order in dot(): what each is, is said only where the values show it.
  const auto said = [](const nlohmann::json& search, const std::string& part) { return search[part]["text"].get<std::string>(); };
  EXPECT_EQ(said(from_eye, "also"), "`viewDir`, the direction to the eye, has the wrong sign") << "V negated: the values show it is V";
  EXPECT_EQ(said(from_eye, "found"), "`reflectDir` is not computed as the homework computes it") << "the half vector is no one change of R";
  EXPECT_EQ(said(as_light, "found"), "`viewDir` is computed as the direction to the light: at every point drawn it holds the homework's L");
  // Written the other way round, dot(reflectDir, viewDir) aligns them the wrong way round: the
  // lines are still both, and no vector is named for either.
  const auto swapped = searched(typed(typed(half, "dot(viewDir, reflectDir)", "dot(reflectDir, viewDir)"), "normalize(-vPosition)", "normalize(vPosition)"));
  EXPECT_EQ(lines_of(swapped), both) << swapped.dump();
  for (const auto* part : {"found", "also"}) {
    if (!swapped.contains(part)) continue;
    for (const auto* vector : {"the direction to the eye", "reflected about the normal"})
      EXPECT_EQ(said(swapped, part).find(vector), std::string::npos) << said(swapped, part);
  }
}

// A value the homework computes otherwise, which the values found to be another of the formula's
// vectors at every pixel drawn, is said as that vector: V computed as L, in the student's names.
TEST(ValueProbesTest, AValueRestoredSaysWhichVectorItHolds) {
  const std::string right = student_with(kStudentShape);
  const auto search = searched(typed(right, "vec3 V = normalize(-vPosition);", "vec3 V = normalize(uLightPosition - vPosition);"));
  ASSERT_TRUE(search.contains("found")) << search.dump();
  EXPECT_EQ(search["found"]["line"].get<int>(), line_of(right, "vec3 V ="));
  EXPECT_EQ(search["found"]["text"].get<std::string>(),
            "`V`, the direction to the eye, is computed as the direction to the light: at every point drawn it holds the homework's L");
  EXPECT_EQ(search["found"]["label"].get<std::string>(), "V computed as L");
}

}  // namespace
}  // namespace shadelab
