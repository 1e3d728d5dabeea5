// The repair search's edits (repair/repair_edits.h) on the mistakes a Phong homework is made of:
// for each, the course's reference with the mistake typed in, an edit that undoes it is among
// those the search's budget reaches.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <set>

#include "course/course_reader.h"
#include "repair/aligned_lines.h"
#include "repair/classmate_edits.h"
#include "repair/live_statements.h"
#include "repair/reference_edits.h"
#include "repair/repair_candidates.h"
#include "repair/repair_edits.h"
#include "repair/said_repair.h"
#include "repair/stage_tokens.h"
#include "repair/value_variation.h"
#include "road/repair_search.h"
#include "shader/glsl_lines.h"
#include "shader/shader_source.h"
#include "support/openapi_check.h"
#include "support/tutorial_program.h"
#include "worker/course_job.h"
#include "worker/pool.h"

using namespace shadelab;

namespace {

std::string glsl_of(const std::string& preset, shader::Stage stage) {
  const course::Course& c = course::builtin_course();
  const course::Preset* p = c.preset(preset);
  EXPECT_NE(p, nullptr) << preset;
  auto unwrapped = shader::unwrap(stage == shader::Stage::vertex ? p->vertex : p->fragment, stage);
  EXPECT_TRUE(static_cast<bool>(unwrapped));
  return unwrapped->glsl;
}

std::string typed(std::string text, const std::string& find, const std::string& replace) {
  const size_t at = text.find(find);
  EXPECT_NE(at, std::string::npos) << find;
  return text.replace(at, find.size(), replace);
}

// A mistake typed into the reference, and the lines an edit may leave that draw as the reference's.
struct Mistake {
  const char* name;
  shader::Stage stage;
  const char* find;
  const char* replace;
  std::vector<std::string> repaired;
};

const Mistake kMistakes[] = {
    {"L not normalised", shader::Stage::fragment, "vec3 L = normalize(uLightPosition - vPosition);", "vec3 L = uLightPosition - vPosition;",
     {"vec3 L = normalize(uLightPosition - vPosition);"}},
    {"pow without max", shader::Stage::fragment, "pow(max(0.0, dot(V, R)), specularAlpha)", "pow(dot(V, R), specularAlpha)",
     {"color += uSpecularColor * uLightColor * pow(max(0.0, dot(V, R)), specularAlpha);"}},
    {"light moved", shader::Stage::fragment, "normalize(uLightPosition - vPosition)", "normalize(uLightPosition + vec3(0.0, 4.0, 0.0) - vPosition)",
     {"vec3 L = normalize(uLightPosition - vPosition);"}},
    {"light halved", shader::Stage::fragment, "normalize(uLightPosition - vPosition)", "normalize(0.5 * uLightPosition - vPosition)",
     {"vec3 L = normalize(uLightPosition - vPosition);"}},
    {"specular colour from the diffuse", shader::Stage::fragment, "color += uSpecularColor", "color += uDiffuseColor",
     {"color += uSpecularColor * uLightColor * pow(max(0.0, dot(V, R)), specularAlpha);"}},
    {"reflect(L, N)", shader::Stage::fragment, "reflect(-L, N)", "reflect(L, N)", {"vec3 R = reflect(-L, N);"}},
    {"view vector away", shader::Stage::fragment, "normalize(-vPosition)", "normalize(vPosition)",
     {"vec3 V = normalize(-vPosition);", "vec3 V = -normalize(vPosition);"}},
    {"N.L not clamped", shader::Stage::fragment, "max(0.0, NdotL)", "NdotL",
     {"vec4 color = uAmbientColor + uDiffuseColor * uLightColor * max(0.0, NdotL);"}},  // its own line: NdotL's is the reference's
    {"normal with the translation", shader::Stage::vertex, "(uMeshToWorldRotMatrix * aVertexNormal).xyz", "(uMeshToWorldMatrix * vec4(aVertexNormal.xyz, 1.0)).xyz",
     {"vNormal = (uMeshToWorldMatrix * vec4(aVertexNormal.xyz, 0.0)).xyz;"}},
    {"position in clip space", shader::Stage::vertex, "vPosition = (uMeshToWorldMatrix * aVertexPosition).xyz;",
     "vPosition = (uWorldToClipSpaceMatrix * uMeshToWorldMatrix * aVertexPosition).xyz;", {"vPosition = (uMeshToWorldMatrix * aVertexPosition).xyz;"}},
    {"reflect's arguments swapped", shader::Stage::fragment, "reflect(-L, N)", "reflect(N, -L)", {"vec3 R = reflect(-L, N);"}},
    {"the cosine clamped at 0.5", shader::Stage::fragment, "max(0.0, NdotL)", "max(0.5, NdotL)",
     {"vec4 color = uAmbientColor + uDiffuseColor * uLightColor * max(0.0, NdotL);"}},
    {"R as the half vector", shader::Stage::fragment, "vec3 R = reflect(-L, N);", "vec3 R = normalize(L + V);", {"vec3 R = reflect(-L, N);"}},
    {"the N.L guard removed", shader::Stage::fragment, "if (NdotL > 0.0) {", "if (true) {", {"if (NdotL > 0.0) {"}},
    {"the diffuse term left out", shader::Stage::fragment, "uDiffuseColor * uLightColor * max(0.0, NdotL)", "vec4(0.0)",
     {"vec4 color = uAmbientColor + uDiffuseColor * uLightColor * max(0.0, NdotL);"}},
    {"V from the light", shader::Stage::fragment, "vec3 V = normalize(-vPosition);", "vec3 V = normalize(uLightPosition - vPosition);",
     {"vec3 V = normalize(-vPosition);"}},
};

}  // namespace

// Each mistake is undone (to the reference's line, or one that draws as it) by an edit within the
// search's budget of candidates, counted over both stages as the search counts them.
TEST(RepairEditsTest, EachMistakeIsUndoneByAnEditOfItsOwnLineWithinTheBudget) {
  for (const Mistake& m : kMistakes) {
    std::string vertex = glsl_of("specular", shader::Stage::vertex), fragment = glsl_of("specular", shader::Stage::fragment);
    std::string& wrong = m.stage == shader::Stage::vertex ? vertex : fragment;
    wrong = typed(wrong, m.find, m.replace);
    const auto edits = repair::program_repair_edits({vertex, fragment}, {glsl_of("specular", shader::Stage::vertex),
                                                                        glsl_of("specular", shader::Stage::fragment)});
    // Its place among the edits of its class (the student's own, or those that read the reference),
    // each class with its own budget.
    size_t found = edits.size();
    for (size_t i = 0; i < edits.size() && found == edits.size(); ++i)
      if (edits[i].stage == m.stage && std::count(m.repaired.begin(), m.repaired.end(), repair::edited_line(wrong, edits[i]))) found = i;
    ASSERT_LT(found, edits.size()) << m.name << ": no edit undoes it";
    const auto place = static_cast<size_t>(std::count_if(edits.begin(), edits.begin() + static_cast<std::ptrdiff_t>(found), [&](const auto& e) {
      return repair::reads_reference(e.kind) == repair::reads_reference(edits[found].kind);
    }));
    const road::RepairBudget budget;
    EXPECT_LT(place, static_cast<size_t>(repair::reads_reference(edits[found].kind) ? budget.reference_candidates : budget.candidates))
        << m.name << ": candidate " << place << " of its class";
  }
}

// No candidate where an edit cannot change what is drawn: a fragment stage that writes one colour
// leaves the vertex stage's varyings and its own lighting dead, and only gl_Position and the
// colour's own line are searched.
TEST(RepairEditsTest, AnAssignmentThatCannotReachTheOutputGetsNoCandidate) {
  const std::string vertex = glsl_of("specular", shader::Stage::vertex);
  const std::string fragment = typed(glsl_of("specular", shader::Stage::fragment), "fragColor = color;", "fragColor = vec4(0.3, 0.8, 0.2, 1.0);");
  const auto edits = repair::program_repair_edits({vertex, fragment});
  ASSERT_FALSE(edits.empty());
  for (const auto& e : edits) {
    const std::string line = repair::edited_line(e.stage == shader::Stage::vertex ? vertex : fragment, e);
    if (e.stage == shader::Stage::vertex) EXPECT_EQ(line.rfind("gl_Position", 0), 0u) << line;
    else EXPECT_EQ(line.rfind("fragColor", 0), 0u) << line;
  }
  const auto all = repair::program_repair_edits({vertex, glsl_of("specular", shader::Stage::fragment)});
  EXPECT_GT(all.size(), 3 * edits.size()) << "the whole program has candidates everywhere";
}

// An output the student's stage never writes is restored from the reference, where it stands
// there (after the statement before it, in the gap a deleted line left), named by what it writes;
// a number the reference writes is never refit, one it does not write is refit to each it does.
TEST(RepairEditsTest, AMissingOutputIsRestoredWhereTheReferenceWritesItAndOnlyForeignNumbersAreRefit) {
  const std::string reference = glsl_of("specular", shader::Stage::vertex);
  const std::string deleted = typed(reference, "vNormal = (uMeshToWorldRotMatrix * aVertexNormal).xyz;", "");
  const auto edits = repair::reference_edits({deleted, shader::Stage::vertex}, {reference, shader::Stage::vertex});
  const auto restored = std::find_if(edits.begin(), edits.end(), [](const auto& e) { return e.kind == repair::RepairKind::statement_restored; });
  ASSERT_NE(restored, edits.end());
  EXPECT_EQ(restored->subject, "vNormal");
  EXPECT_EQ(repair::with_edit(deleted, *restored).find("vNormal = (uMeshToWorldRotMatrix * aVertexNormal).xyz;"),
            reference.find("vNormal = (uMeshToWorldRotMatrix * aVertexNormal).xyz;"))
      << "restored where it was deleted";
  EXPECT_EQ(restored->line, shader::lines_of(reference.substr(0, reference.find("vNormal ="))).size());
  EXPECT_EQ(repair::repair_words(*restored), "`vNormal` is never written: the fragment stage reads what the vertex stage writes there");
  EXPECT_EQ(std::count_if(edits.begin(), edits.end(), [](const auto& e) { return e.kind == repair::RepairKind::statement_restored; }), 1);

  // A write of a name the stage writes elsewhere too: the specular term's accumulation deleted.
  const std::string fragment = glsl_of("specular", shader::Stage::fragment);
  const std::string accumulation = "color += uSpecularColor * uLightColor * pow(max(0.0, dot(V, R)), specularAlpha);";
  const std::string unlit = typed(fragment, "        " + accumulation + "\n", "");
  const auto fragment_edits = repair::reference_edits({unlit, shader::Stage::fragment}, {fragment, shader::Stage::fragment});
  const auto write = std::find_if(fragment_edits.begin(), fragment_edits.end(), [](const auto& e) { return e.kind == repair::RepairKind::write_restored; });
  ASSERT_NE(write, fragment_edits.end());
  EXPECT_EQ(repair::unspaced(repair::with_edit(unlit, *write)), repair::unspaced(fragment)) << "restored after the statement before it";
  EXPECT_EQ(write->line, shader::lines_of(fragment.substr(0, fragment.find(accumulation))).size());
  EXPECT_EQ(repair::repair_words(*write), "`color` misses a statement the homework has here: it writes `color` once more than yours does");
  EXPECT_FALSE(std::any_of(fragment_edits.begin(), fragment_edits.end(), [](const auto& e) { return e.kind == repair::RepairKind::statement_restored; }))
      << "the stage writes its colour: nothing is never written";

  for (const auto& e : repair::reference_edits({fragment, shader::Stage::fragment}, {fragment, shader::Stage::fragment}))
    ADD_FAILURE() << "the reference itself has an edit: " << repair::edited_line(fragment, e);
  const std::string halved = typed(fragment, "float specularAlpha = 6.0;", "float specularAlpha = 3.0;");
  std::vector<std::string> refits;
  for (const auto& e : repair::reference_edits({halved, shader::Stage::fragment}, {fragment, shader::Stage::fragment}))
    if (e.kind == repair::RepairKind::literal_refit) refits.push_back(repair::edited_line(halved, e));
  EXPECT_EQ(refits, (std::vector<std::string>{"float specularAlpha = 6.0;", "float specularAlpha = 0.0;"}));
}

// A varying made flat in both stages is one edit of both, read as the reference's lines: `flat`
// removed from each (the qualifier must match between the stages: neither alone would link).
// Flat in one stage alone does not link, so it is no mistake of this kind and gets no such edit.
TEST(RepairEditsTest, AVaryingMadeFlatInBothStagesIsOneEditOfBoth) {
  const std::string vertex = glsl_of("specular", shader::Stage::vertex), fragment = glsl_of("specular", shader::Stage::fragment);
  const std::string flat_vertex = typed(vertex, "out vec3 vNormal;", "flat out vec3 vNormal;");
  const std::string flat_fragment = typed(fragment, "in vec3 vNormal;", "flat in vec3 vNormal;");
  const auto flat_removed = [](const auto& edits) {
    return std::find_if(edits.begin(), edits.end(), [](const auto& e) { return e.kind == repair::RepairKind::flat_removed; });
  };
  const auto edits = repair::program_repair_edits({flat_vertex, flat_fragment}, {vertex, fragment});
  const auto found = flat_removed(edits);
  ASSERT_NE(found, edits.end());
  EXPECT_EQ(found, edits.begin()) << "the first tried: both lines then read as the reference's";
  EXPECT_TRUE(found->reads_as_reference);
  EXPECT_EQ(found->stage, shader::Stage::vertex);
  EXPECT_EQ(found->subject, "vNormal");
  EXPECT_EQ(repair::with_edit(flat_vertex, *found), vertex);
  ASSERT_TRUE(found->other_stage.has_value());
  EXPECT_EQ(flat_fragment.substr(0, found->other_stage->begin) + found->other_stage->with + flat_fragment.substr(found->other_stage->end),
            fragment);
  EXPECT_NE(repair::repair_words(*found).find("`vNormal` is declared `flat`"), std::string::npos) << repair::repair_words(*found);
  const auto one_stage = repair::program_repair_edits({flat_vertex, fragment}, {vertex, fragment});
  EXPECT_EQ(flat_removed(one_stage), one_stage.end());
}

// A student's extra statements (an `if` of their own, a write of one field) do not hide the
// statement they changed: the guard's condition and the first write of `color` are still
// restored from the reference.
TEST(RepairEditsTest, AStudentsExtraIfOrFieldWriteDoesNotHideTheChangedStatement) {
  const std::string reference = glsl_of("specular", shader::Stage::fragment);
  const std::string extra = typed(reference, "    fragColor = color;", "    if (gl_FragCoord.x < -1.0) color.r += 1.0;\n    fragColor = color;");
  const auto restored = [](const std::string& wrong, const std::string& ref) {
    std::vector<std::string> lines;
    for (const auto& e : repair::reference_edits({wrong, shader::Stage::fragment}, {ref, shader::Stage::fragment}))
      if (e.kind != repair::RepairKind::literal_refit) lines.push_back(repair::edited_line(wrong, e));
    return lines;
  };
  const auto guard = restored(typed(extra, "if (NdotL > 0.0) {", "if (true) {"), reference);
  EXPECT_NE(std::find(guard.begin(), guard.end(), "if (NdotL > 0.0) {"), guard.end());
  const auto diffuse = restored(typed(extra, "uDiffuseColor * uLightColor * max(0.0, NdotL)", "vec4(0.0)"), reference);
  EXPECT_NE(std::find(diffuse.begin(), diffuse.end(), "vec4 color = uAmbientColor + uDiffuseColor * uLightColor * max(0.0, NdotL);"), diffuse.end());
}

// A line the student wrote as the reference writes it gets no edit: with L and R both negated,
// negating the normal draws the reference's frames too (reflect ignores N's sign, N.L keeps its
// own), but "`vNormal` has the wrong sign" would name a change the student never made.
TEST(RepairEditsTest, ALineWrittenAsTheReferenceWritesItIsNeverEdited) {
  const std::string vertex = glsl_of("specular", shader::Stage::vertex), fragment = glsl_of("specular", shader::Stage::fragment);
  const std::string wrong = typed(typed(fragment, "dot(V, R)", "dot(V, -R)"), "vec3 L = normalize(uLightPosition - vPosition);",
                                  "vec3 L = -normalize(uLightPosition - vPosition);");
  const auto edits = repair::program_repair_edits({vertex, wrong}, {vertex, fragment});
  const auto vertex_lines = shader::lines_of(vertex);
  const auto wrong_lines = shader::lines_of(wrong);
  bool changed_line_edited = false;
  for (const auto& e : edits) {
    if (e.kind == repair::RepairKind::statement_restored) continue;
    const auto& lines = e.stage == shader::Stage::vertex ? vertex_lines : wrong_lines;
    const std::string_view line = lines[e.line - 1];
    EXPECT_TRUE(line.find("-R") != std::string_view::npos || line.find("-normalize") != std::string_view::npos)
        << repair::to_string(e.kind) << " at an unchanged line: " << line;
    changed_line_edited = changed_line_edited || e.kind == repair::RepairKind::negation_removed;
  }
  EXPECT_TRUE(changed_line_edited) << "each negation is still undone at its own line";
}

// A student who names the reference's locals otherwise still wrote its lines: the names align
// from their declarations, and only a line that differs by more than them is edited.
TEST(RepairEditsTest, AStudentsOwnNamesForTheLocalsAlignWithTheReferences) {
  const std::string reference = glsl_of("specular", shader::Stage::fragment);
  const std::string student = typed(typed(typed(typed(typed(reference, "vec3 N = normalize(vNormal);", "vec3 n = normalize(vNormal);"),
                                                        "vec3 L = normalize(", "vec3 toLight = normalize("),
                                                  "dot(N, L)", "dot(n, toLight)"),
                                            "vec3 R = reflect(-L, N);", "vec3 mirrored = reflect(-toLight, n);"),
                                      "dot(V, R)", "dot(V, mirrored)");
  const repair::AlignedLines lines(student, reference);
  EXPECT_TRUE(lines.reads_as_reference("    vec3 mirrored = reflect(-toLight, n);  // R"));
  EXPECT_TRUE(lines.reads_as_reference("float NdotL = dot(n, toLight);"));
  EXPECT_FALSE(lines.reads_as_reference("vec3 mirrored = reflect(-n, toLight);")) << "the arguments swapped";
  EXPECT_FALSE(lines.reads_as_reference("vec3 mirrored = reflect(toLight, n);")) << "a sign";
  EXPECT_FALSE(lines.reads_as_reference("float NdotL = dot(N, L);")) << "a name aligned with another never reads as itself";
  EXPECT_FALSE(lines.reads_as_reference("vec4 color = uAmbientColor + uSpecularColor * uLightColor * max(0.0, NdotL);"))
      << "a uniform aligns only with itself";
  // A declaration the student got wrong aligns its name once an edit mends it.
  const std::string view_away =
      typed(typed(student, "vec3 V = normalize(-vPosition);", "vec3 toEye = normalize(vPosition);"), "dot(V, mirrored)", "dot(toEye, mirrored)");
  const repair::AlignedLines mended(view_away, reference);
  EXPECT_FALSE(mended.reads_as_reference("vec3 toEye = normalize(vPosition);"));
  EXPECT_TRUE(mended.reads_as_reference("vec3 toEye = normalize(-vPosition);"));
  // So the search edits the line the student changed, not the reflection they wrote as the
  // reference does (negating R's -L would draw the same frames).
  const auto edits = repair::program_repair_edits({glsl_of("specular", shader::Stage::vertex), view_away},
                                                 {glsl_of("specular", shader::Stage::vertex), reference});
  const auto student_lines = shader::lines_of(view_away);
  bool view_negated = false;
  for (const auto& e : edits) {
    if (e.stage != shader::Stage::fragment || e.kind == repair::RepairKind::statement_restored || e.kind == repair::RepairKind::write_restored) continue;
    EXPECT_EQ(student_lines[e.line - 1].find("reflect("), std::string_view::npos) << repair::to_string(e.kind);
    view_negated = view_negated || (e.kind == repair::RepairKind::negation_added && student_lines[e.line - 1].find("toEye =") != std::string_view::npos);
  }
  EXPECT_TRUE(view_negated) << "the view vector's own line is negated";
}

// Two locals whose declarations both read as none of the reference's still align: by a use where
// each stands beside the other (`dot(viewDir, reflectDir)` as `dot(V, R)`), then the one local of
// its type each program leaves.
TEST(RepairEditsTest, TwoLocalsWhoseDeclarationsBothChangedAlignByTheirUse) {
  const std::string reference = glsl_of("specular", shader::Stage::fragment);
  const std::string student =
      typed(typed(typed(reference, "vec3 V = normalize(-vPosition);", "vec3 viewDir = normalize(vPosition);"), "vec3 R = reflect(-L, N);",
                  "vec3 reflectDir = normalize(L + viewDir);"),
            "dot(V, R)", "dot(viewDir, reflectDir)");
  const repair::AlignedLines lines(student, reference);
  EXPECT_EQ(lines.reference_name("viewDir", ""), "V");
  EXPECT_EQ(lines.reference_name("reflectDir", ""), "R");
}

// The reference's name for a student's local, which a repair's words say in the homework's terms:
// an aligned name, a name both declare, one a mended declaration aligns; none for a uniform or an
// expression.
TEST(RepairEditsTest, AStudentsLocalIsNamedAsTheReferencesVector) {
  const std::string reference = glsl_of("specular", shader::Stage::fragment);
  const std::string student =
      typed(typed(typed(typed(reference, "vec3 L = normalize(", "vec3 toLight = normalize("), "dot(N, L)", "dot(N, toLight)"),
                  "vec3 V = normalize(-vPosition);", "vec3 toEye = normalize(vPosition);"),
            "dot(V, R)", "dot(toEye, R)");
  const repair::AlignedLines lines(student, reference);
  EXPECT_EQ(lines.reference_name("toLight", "float NdotL = dot(N, toLight);"), "L");
  EXPECT_EQ(lines.reference_name("N", "vec3 N = normalize(vNormal);"), "N") << "a name both declare is one variable";
  EXPECT_EQ(lines.reference_name("toEye", "vec3 toEye = normalize(-vPosition);"), "V") << "the edit mends its declaration";
  EXPECT_EQ(lines.reference_name("toEye", "vec3 toEye = -normalize(vPosition);"), "V") << "it stands in for V in dot(toEye, R)";
  const repair::AlignedLines unused(typed(student, "dot(toEye, R)", "dot(toLight, R)"), reference);
  EXPECT_EQ(unused.reference_name("toEye", "vec3 toEye = normalize(vPosition);"), "") << "declared unlike V, and used nowhere";
  EXPECT_EQ(lines.reference_name("uLightColor", "vec4 color = uAmbientColor;"), "");
  // A uniform where the reference reads L is the uniform still, never "the direction to the light".
  const std::string no_l = typed(typed(reference, "vec3 L = normalize(uLightPosition - vPosition);", ""), "dot(N, L)", "dot(N, uLightPosition)");
  const repair::AlignedLines uniform_for_l(no_l, reference);
  EXPECT_EQ(uniform_for_l.reference_name("uLightPosition", "float NdotL = dot(N, uLightPosition);"), "");
  EXPECT_EQ(lines.reference_name("dot(N, toLight)", "float NdotL = dot(N, toLight);"), "");
  // The words: the student's name, and what it is in the homework's formula.
  repair::RepairEdit e;
  e.kind = repair::RepairKind::normalised;
  e.subject = "toLight";
  EXPECT_EQ(repair::repair_words(e, "the direction to the light"), "`toLight` is not normalised: the direction to the light must be a unit vector");
  e.kind = repair::RepairKind::negation_added;
  e.subject = "toEye";
  EXPECT_EQ(repair::repair_words(e, "the direction to the eye"), "`toEye`, the direction to the eye, has the wrong sign");
  EXPECT_EQ(repair::repair_words(e), "`toEye` has the wrong sign");
}

// A restored value is the reference's text, named and never shown; where it differs from the
// student's by one change a student makes, it is said in that change's words, of the student's
// own text. Where it differs by more, no change is claimed.
TEST(RepairEditsTest, ARestoredValueIsSaidAsTheOneChangeItMakes) {
  const std::string reference = glsl_of("specular", shader::Stage::fragment);
  const auto words_in = [&](const std::string& wrong, const std::string& restored_line) {
    for (const auto& e : repair::reference_edits({wrong, shader::Stage::fragment}, {reference, shader::Stage::fragment}))
      if (e.kind == repair::RepairKind::value_restored && repair::edited_line(wrong, e) == restored_line) return repair::repair_words(e);
    ADD_FAILURE() << "no value restored to " << restored_line;
    return std::string();
  };
  const auto words = [&](const std::string& find, const std::string& replace, const std::string& restored_line) {
    return words_in(typed(reference, find, replace), restored_line);
  };
  const std::string color = "vec4 color = uAmbientColor + uDiffuseColor * uLightColor * max(0.0, NdotL);";
  EXPECT_EQ(words("normalize(uLightPosition - vPosition)", "(uLightPosition - vPosition)", "vec3 L = normalize(uLightPosition - vPosition);"),
            "`L` is not normalised: a direction must be a unit vector");
  // A sign inside normalize(...) is the direction's own: said of the local the student writes it
  // into (the homework's V, L), not of what it normalises (it read "`vPosition` has the wrong sign").
  EXPECT_EQ(words("normalize(-vPosition)", "normalize(vPosition)", "vec3 V = normalize(-vPosition);"), "`V` has the wrong sign");
  EXPECT_EQ(words("normalize(uLightPosition - vPosition)", "normalize(vPosition - uLightPosition)", "vec3 L = normalize(uLightPosition - vPosition);"),
            "`L` has the wrong sign");
  EXPECT_EQ(words("max(0.0, NdotL)", "NdotL", color), "`NdotL` is not clamped at 0: a cosine below 0 must count as 0, max(0.0, ...)");
  EXPECT_EQ(words("uDiffuseColor * uLightColor", "uSpecularColor * uLightColor", color), "`uSpecularColor` is not the value the homework uses here");
  EXPECT_EQ(words("uAmbientColor + uDiffuseColor", "uAmbientColor - uDiffuseColor", color),
            "`uDiffuseColor * uLightColor * max(0.0, NdotL)` is subtracted where the homework adds it");
  const std::string vertex = glsl_of("specular", shader::Stage::vertex);
  const std::string w0 = typed(vertex, "uWorldToClipSpaceMatrix * uMeshToWorldMatrix * aVertexPosition",
                               "uWorldToClipSpaceMatrix * uMeshToWorldMatrix * vec4(aVertexPosition.xyz, 0.0)");
  std::vector<std::string> w_words;
  for (const auto& e : repair::reference_edits({w0, shader::Stage::vertex}, {vertex, shader::Stage::vertex}))
    if (e.kind == repair::RepairKind::value_restored) w_words.push_back(repair::repair_words(e));
  EXPECT_EQ(w_words, std::vector<std::string>{"`aVertexPosition` is a point, so its w must be 1: with w = 0 the matrix's translation is lost"});
  // The normal given w = 1 and the mesh's whole matrix: it moves with the mesh. Said of the
  // varying, with the matrix the homework transforms it by (it read "`vNormal` is not computed as
  // the homework computes it").
  const std::string moved = typed(vertex, "(uMeshToWorldRotMatrix * aVertexNormal).xyz", "(uMeshToWorldMatrix * vec4(aVertexNormal.xyz, 1.0)).xyz");
  std::vector<std::string> moved_words;
  for (const auto& e : repair::reference_edits({moved, shader::Stage::vertex}, {vertex, shader::Stage::vertex}))
    if (e.kind == repair::RepairKind::value_restored) moved_words.push_back(repair::repair_words(e));
  EXPECT_EQ(moved_words, std::vector<std::string>{"`vNormal` is a direction, so its w must be 0: with w = 1 the matrix's translation moves it "
                                                  "(the homework transforms it by `uMeshToWorldRotMatrix`)"});
  EXPECT_EQ(words("vec3 R = reflect(-L, N);", "vec3 R = normalize(L + V);", "vec3 R = reflect(-L, N);"), "`R` is not computed as the homework computes it")
      << "a term replaced by another is more than one change";
  // More than one change, where the student's value is the same everywhere and the reference's is
  // not: that is said, with the inputs the reference's value reads itself.
  EXPECT_EQ(words("normalize(-vPosition)", "vec3(0.0, 0.0, 1.0)", "vec3 V = normalize(-vPosition);"),
            "`V` is the same at every point, where the homework computes it at each point from `vPosition`");
  EXPECT_EQ(words("normalize(uLightPosition - vPosition)", "normalize(uLightPosition)", "vec3 L = normalize(uLightPosition - vPosition);"),
            "`L` is the same at every point, where the homework computes it at each point from `vPosition`");
  EXPECT_EQ(words("uDiffuseColor * uLightColor * max(0.0, NdotL)", "vec4(0.0)", color),
            "`color` is the same at every point, where the homework's changes from point to point")
      << "the reference's colour reads NdotL, a local written from the inputs";
  // Not known to be constant: a local (it may hide an input), or a function of the stage's own.
  EXPECT_EQ(words("normalize(-vPosition)", "normalize(L + N)", "vec3 V = normalize(-vPosition);"),
            "`V` is not computed as the homework computes it");
  const std::string own_function =
      typed(typed(reference, "void main(void) {", "vec3 eye() { return vec3(0.0, 0.0, 1.0); }\nvoid main(void) {"), "normalize(-vPosition)", "eye()");
  EXPECT_EQ(words_in(own_function, "vec3 V = normalize(-vPosition);"), "`V` is not computed as the homework computes it");
}

// What varies from point to point: the stage's inputs, and what it writes from them however many
// writes away; what is constant: uniforms, numbers and the built-ins of them, nothing else.
TEST(RepairEditsTest, AValueVariesWhereItReadsAnInputThroughAnyLocal) {
  const std::string glsl = glsl_of("specular", shader::Stage::fragment);
  const auto t = shader::tokens_of(glsl);
  const repair::StageVariation stage(t);
  const auto value = [](const std::string& text) { return shader::tokens_of(text); };
  for (const std::string v : {"vPosition", "-vPosition.xyz", "R", "dot(V, R)", "NdotL", "gl_FragCoord.x"}) {
    const auto tokens = value(v);
    EXPECT_TRUE(stage.varies(tokens)) << v;
    EXPECT_FALSE(stage.constant(tokens)) << v;
  }
  for (const std::string v : {"vec3(0.0, 0.0, 1.0)", "normalize(uLightPosition)", "uAmbientColor * 0.5", "uLightPosition.xyz"}) {
    const auto tokens = value(v);
    EXPECT_TRUE(stage.constant(tokens)) << v;
    EXPECT_FALSE(stage.varies(tokens)) << v;
  }
  EXPECT_FALSE(stage.constant(value("eye()"))) << "a function of the stage's own may read an input";
  EXPECT_FALSE(stage.varies(value("eye()"))) << "nor is it known to vary";
  EXPECT_EQ(stage.inputs_read(value("normalize(uLightPosition - vPosition) + vNormal - vPosition")),
            (std::vector<std::string>{"vPosition", "vNormal"}));
}

// An edit says what is wrong in the homework's words and leaves the rest of the stage as it was.
TEST(RepairEditsTest, AnEditChangesItsSpanAloneAndSaysWhatIsWrong) {
  const std::string glsl = "void main() {\n    vec3 L = uLightPosition - vPosition;\n}\n";
  const auto edits = repair::repair_edits({glsl, shader::Stage::fragment});
  ASSERT_FALSE(edits.empty());
  const repair::RepairEdit& first = edits.front();
  EXPECT_EQ(first.kind, repair::RepairKind::normalised);
  EXPECT_EQ(first.line, 2);
  EXPECT_EQ(repair::with_edit(glsl, first), "void main() {\n    vec3 L = normalize(uLightPosition - vPosition);\n}\n");
  EXPECT_EQ(repair::repair_words(first), "`L` is not normalised: a direction must be a unit vector");

  // A number that scales one name is said of that name: the ambient colour is doubled.
  const std::string doubled = "void main() {\n    fragColor = 2.0 * uAmbientColor + uDiffuseColor * 0.5;\n}\n";
  std::vector<std::string> words;
  for (const auto& e : repair::repair_edits({doubled, shader::Stage::fragment}))
    if (e.kind == repair::RepairKind::factor_removed) words.push_back(repair::repair_words(e) + " / " + repair::repair_label(e));
  EXPECT_EQ(words, (std::vector<std::string>{
                       "`uAmbientColor` is multiplied by `2.0` here: the homework uses `uAmbientColor` as it is / `uAmbientColor` scaled by a number",
                       "`uDiffuseColor` is multiplied by `0.5` here: the homework uses `uDiffuseColor` as it is / `uDiffuseColor` scaled by a number"}));
}
// A condition is live where its block, or an else block after it, is: the names it reads reach
// the output through the branch taken.
// The kinds are one table (repair/repair_kind.cpp): each kind has its row, its name reads back as
// the kind, its words and label say something, and the API document lists exactly the table's
// names wherever a repair's kind is described.
TEST(RepairKindsTest, EachKindIsOneRowWhoseNameTheApiDocumentLists) {
  std::vector<std::string> names;
  for (int k = 0; k <= static_cast<int>(repair::RepairKind::condition_restored); ++k) {
    const auto kind = static_cast<repair::RepairKind>(k);
    EXPECT_EQ(repair::info(kind).kind, kind) << k;
    EXPECT_EQ(repair::repair_kind_named(repair::to_string(kind)), kind) << repair::to_string(kind);
    repair::RepairEdit e;
    e.kind = kind;
    e.subject = "L";
    EXPECT_NE(repair::repair_words(e).find("`L`"), std::string::npos) << repair::to_string(kind) << ": " << repair::repair_words(e);
    EXPECT_FALSE(repair::repair_label(e, "L").empty()) << repair::to_string(kind);
    names.emplace_back(repair::to_string(kind));
  }
  EXPECT_FALSE(repair::repair_kind_named("not_a_kind"));
  int listed = 0;
  const std::function<void(const nlohmann::json&)> visit = [&](const nlohmann::json& j) {
    if (j.is_object() && j.contains("enum") && j["enum"].is_array() && !j["enum"].empty() && j["enum"][0] == names.front()) {
      EXPECT_EQ(j["enum"].get<std::vector<std::string>>(), names);
      ++listed;
    }
    if (j.is_structured())
      for (const auto& child : j) visit(child);
  };
  visit(testkit::openapi());
  EXPECT_GE(listed, 2) << "a repair search's found and also";
}

TEST(LiveStatementsTest, AConditionIsLiveWhereAnyOfItsBranchesIs) {
  const std::string glsl =
      "out vec4 fragColor;\nin vec3 vN;\nvoid main() {\n  float c = vN.x;\n  float unused = 2.0;\n  float d = vN.y;\n"
      "  if (c > 0.0) { d += 1.0; } else { fragColor = vec4(1.0); }\n  if (unused > 1.0) { d = 0.0; }\n}\n";
  const repair::StageLiveness live = repair::fragment_liveness({glsl, shader::Stage::fragment});
  EXPECT_TRUE(live.live_names.count("c")) << "read by a condition whose else block writes the output";
  EXPECT_TRUE(live.live_names.count("vN"));
  EXPECT_FALSE(live.live_names.count("unused")) << "read only by a condition whose block is dead";
  EXPECT_FALSE(live.live_names.count("d"));
  EXPECT_TRUE(live.dead(glsl.find("float unused")));
  EXPECT_TRUE(live.dead(glsl.find("float d")));
  EXPECT_FALSE(live.dead(glsl.find("float c")));
}

// A screened candidate that hangs is stopped at its share of the deadlines (RepairBudget's
// screen_deadline_share), not the grade's whole: the pool reads the job's share.
TEST(RepairSearchTest, AJobsShareOfTheDeadlinesStopsAHangEarlier) {
  worker::PoolConfig config;
  config.workers = 1;
  config.executable = SHADELAB_CLI;
  config.warm_up = worker::WarmUp::none;
  config.compile_deadline = config.render_deadline = std::chrono::milliseconds(4000);
  worker::WorkerPool pool(config);
  const course::Course& c = course::builtin_course();
  shader::ShaderFile vertex{"loop_vert.glsl", "#version 300 es\nin vec4 aVertexPosition;\nvoid main() {\n  int i = gl_VertexID % 3;\n"
                            "  gl_Position = vec4(i == 1 ? 3.0 : -1.0, i == 2 ? 3.0 : -1.0, 0.0, 1.0);\n}\n"};
  shader::ShaderFile fragment{"loop_frag.glsl", "#version 300 es\nprecision highp float;\nout vec4 c;\nvoid main() {\n  float s = gl_FragCoord.x;\n"
                              "  while (true) { s = sin(sin(sin(sin(s * 1.0001 + 0.5)))); if (s > 2.0) break; }\n  c = vec4(s);\n}\n"};
  worker::Job job = worker::course_job(c, worker::JobKind::render, vertex, fragment);
  std::string mesh;
  ASSERT_TRUE(worker::attach_course_mesh(c, c.default_mesh, job, mesh).ok());
  job.request.width = job.request.height = 16;
  job.request.frames = 1;
  job.deadline_share = 0.1;
  auto submitted = pool.submit(worker::to_message(job, mesh));
  ASSERT_TRUE(submitted.ok());
  const worker::JobResult result = submitted->get();
  ASSERT_FALSE(result.answered) << "an endless loop never answers";
  EXPECT_EQ(result.error.code, ErrorCode::render_timeout) << result.error.message;
  // Stopped at the share: 400 ms of CPU time, or on a machine too busy to give the worker a
  // quarter of a core, the wall-clock backstop of four times that (the whole deadlines: 4000 and
  // 16000 ms).
  const std::string& why = result.error.message;
  EXPECT_TRUE(why.find("used more than 400 ms of CPU time") != std::string::npos || why.find("within 1600 ms of wall-clock time") != std::string::npos)
      << why;
}

// A student who names their values as a classmate does (`reflectDir`, where the reference writes
// R) gets the classmate's value of it as an edit, where the course's reference offers none; what
// the reference offers already is not offered twice, and the nearest classmate is the one whose
// lines the student's are written like.
TEST(ClassmateEditsTest, AClassmateWhoNamesAValueAsTheStudentDoesOffersTheirValueOfIt) {
  const std::string vertex = glsl_of("specular", shader::Stage::vertex), reference = glsl_of("specular", shader::Stage::fragment);
  const std::string classmate = testkit::with_tutorial_main(reference);
  // The half vector through a local of its own: two locals the reference's cannot align one to
  // one (repair/student_names.h), so that only the classmate names reflectDir.
  const std::string student = typed(classmate, "vec3 reflectDir = reflect(-lightDir, norm);",
                                    "vec3 halfway = normalize(lightDir + viewDir);\n        vec3 reflectDir = halfway;");
  const auto restores_reflect_dir = [](const repair::RepairEdit& e) { return e.kind == repair::RepairKind::value_restored && e.subject == "reflectDir"; };

  const auto own = repair::program_repair_edits({vertex, student}, {vertex, reference});
  EXPECT_FALSE(std::any_of(own.begin(), own.end(), restores_reflect_dir)) << "the reference never writes reflectDir";
  const auto offered = repair::classmate_edits({vertex, student}, {vertex, reference}, {{vertex, classmate}});
  const auto restored = std::find_if(offered.begin(), offered.end(), restores_reflect_dir);
  ASSERT_NE(restored, offered.end());
  EXPECT_EQ(repair::edited_line(student, *restored), "vec3 reflectDir = reflect(-lightDir, norm);");
  EXPECT_TRUE(repair::writes_reference_text(restored->kind)) << "a classmate's text is named, never shown";
  for (const auto& e : offered) {
    EXPECT_TRUE(repair::reads_reference(e.kind)) << "only edits that read the other program";
    for (const auto& o : own)
      EXPECT_FALSE(o.stage == e.stage && o.begin == e.begin && o.end == e.end && o.with == e.with) << "offered twice: " << e.with;
  }
  EXPECT_TRUE(repair::classmate_edits({vertex, student}, {vertex, reference}, {{vertex, reference}}).empty())
      << "the reference as a classmate offers nothing the reference does not";
  // To a student written as the reference is, the tutorial's values and conditions name its own
  // locals (`diff > 0.0`), which that student never declares: none could compile, none is offered.
  for (const auto& e : repair::classmate_edits({vertex, reference}, {vertex, reference}, {{vertex, classmate}}))
    ADD_FAILURE() << "offered an edit naming a local the student never declares: " << e.with;

  // Nearest: the classmate whose lines are the student's, before the reference; a copy counts once.
  const repair::ProgramReading read({vertex, student});
  const auto nearest = repair::nearest_classmates(read, {{vertex, reference}, {vertex, classmate}, {vertex, classmate}}, 3);
  ASSERT_EQ(nearest.size(), 2u);
  EXPECT_EQ(nearest[0].fragment, classmate);
  EXPECT_EQ(nearest[1].fragment, reference);
  EXPECT_EQ(repair::nearest_classmates(read, {{vertex, reference}, {vertex, classmate}}, 1).front().fragment, classmate);
}

// What a search tries, in its order, decided without a worker (repair/repair_candidates.h): the
// class's singles first, each kind within its count, every candidate the student's program with
// its edits made and nothing else, and pairs within their count, none twice, none of two edits
// that touch.
TEST(RepairCandidatesTest, TheClassComesFirstEachKindWithinItsCountAndNoPairTouchesOrRepeats) {
  const course::Course& c = course::builtin_course();
  const course::Preset* specular = c.preset("specular");
  ASSERT_NE(specular, nullptr);
  const std::string reference = glsl_of("specular", shader::Stage::fragment);
  const std::string classmate = testkit::with_tutorial_main(reference);
  const shader::ShaderFile vertex = specular->vertex;
  const shader::ShaderFile fragment{"phong_frag.glsl", typed(classmate, "vec3 reflectDir = reflect(-lightDir, norm);",
                                                             "vec3 halfway = normalize(lightDir + viewDir);\n        vec3 reflectDir = halfway;")};
  const auto program = repair::repair_program(vertex, fragment, specular->vertex, specular->fragment,
                                             {{specular->vertex, {"classmate.glsl", classmate}}});
  ASSERT_TRUE(program.ok()) << program.error().message;
  ASSERT_EQ(program->classmates.size(), 1u);

  const repair::CandidateCounts counts{40, 4, 3, 3, 4};
  const size_t offered = repair::class_edits(*program, counts).size();
  ASSERT_GT(offered, 0u) << "the classmate writes reflectDir as the homework computes it";
  const auto singles = repair::single_candidates(*program, counts);
  const size_t from_class = std::min<size_t>(offered, 3);
  int own = 0, reads = 0;
  for (size_t i = 0; i < singles.size(); ++i) {
    const auto& s = singles[i];
    ASSERT_EQ(s.edits.size(), 1u);
    EXPECT_EQ(s.from_class, i < from_class) << "candidate " << i;
    if (!s.from_class) ++(repair::reads_reference(s.edits.front().kind) ? reads : own);
    const repair::RepairEdit& e = s.edits.front();
    const auto& edited = e.stage == shader::Stage::vertex ? s.vertex : s.fragment;
    const auto& kept = e.stage == shader::Stage::vertex ? s.fragment : s.vertex;
    EXPECT_EQ(edited.text, repair::with_edit((*program)[e.stage].source.glsl, e)) << "candidate " << i;
    if (!e.other_stage) {
      EXPECT_EQ(kept.text, (e.stage == shader::Stage::vertex ? fragment : vertex).text) << "candidate " << i;
    }
  }
  EXPECT_EQ(own, counts.own);
  EXPECT_LE(reads, counts.reference);
  EXPECT_TRUE(repair::single_candidates(*program, {0, 0, 0, 0, 0}).empty());

  // The nearest single, one that drew nearer than the student's own program, is paired with the
  // others after the class's pairs.
  const auto touch = [](const repair::RepairEdit& a, const repair::RepairEdit& b) { return a.stage == b.stage && a.begin <= b.end && b.begin <= a.end; };
  size_t nearest = singles.size();  // a single another touches, so that pairing it has one pair to leave out
  for (size_t i = 0; i < singles.size() && nearest == singles.size(); ++i)
    for (size_t j = 0; j < singles.size(); ++j)
      if (i != j && touch(singles[i].edits.front(), singles[j].edits.front())) nearest = i;
  ASSERT_LT(nearest, singles.size());
  std::vector<double> distances(singles.size(), 0.5);
  distances[nearest] = 0.1;
  const auto pairs = repair::pair_candidates(*program, singles, distances, 0.4, counts);
  ASSERT_FALSE(pairs.empty());
  EXPECT_LE(pairs.size(), static_cast<size_t>(counts.pairs));
  const auto all = repair::pair_candidates(*program, singles, distances, 0.4, {40, 4, 3, 3, 1000});
  ASSERT_GT(all.size(), pairs.size());
  std::set<std::pair<std::string, std::string>> seen;
  for (const auto& pair : all) {
    ASSERT_EQ(pair.edits.size(), 2u);
    const repair::RepairEdit &a = pair.edits[0], &b = pair.edits[1];
    EXPECT_FALSE(touch(a, b)) << "two edits that touch: " << a.with << " and " << b.with;
    EXPECT_FALSE(repair::smaller(b, a)) << "a pair's edits in the singles' order of size";
    EXPECT_TRUE(seen.emplace(a.with + "@" + std::to_string(a.begin), b.with + "@" + std::to_string(b.begin)).second) << "a pair twice";
  }
  const auto same = [](const repair::RepairEdit& x, const repair::RepairEdit& y) { return x.stage == y.stage && x.begin == y.begin && x.with == y.with; };
  const auto is_single = [&](const repair::RepairEdit& e, size_t i) { return same(e, singles[i].edits.front()); };
  // The class's pairs first, then those of two lines that each read as the reference's.
  const auto& first = pairs.front().edits;
  const size_t as_reference = static_cast<size_t>(
      std::count_if(singles.begin(), singles.end(), [](const auto& s) { return s.edits.front().reads_as_reference; }));
  if (from_class >= 2) {
    EXPECT_TRUE((is_single(first[0], 0) && is_single(first[1], 1)) || (is_single(first[0], 1) && is_single(first[1], 0)))
        << "the class's two first singles are the first pair";
  } else if (as_reference >= 2) {
    EXPECT_TRUE(first[0].reads_as_reference && first[1].reads_as_reference) << "two lines read as the reference's are the first pair";
  }
  EXPECT_TRUE(std::any_of(all.begin(), all.end(), [&](const auto& pair) {
    return is_single(pair.edits[0], nearest) || is_single(pair.edits[1], nearest);
  })) << "the single nearer than the student's own program is paired";
  const auto from_the_class = [&](const repair::RepairEdit& e) {
    for (size_t i = 0; i < from_class; ++i)
      if (is_single(e, i)) return true;
    return false;
  };
  for (const auto& pair : all) {
    const repair::RepairEdit &a = pair.edits[0], &b = pair.edits[1];
    EXPECT_TRUE((from_the_class(a) && from_the_class(b)) || (a.reads_as_reference && b.reads_as_reference) ||
                is_single(a, nearest) || is_single(b, nearest))
        << "a pair is two of the class's, two lines read as the reference's, or has the nearest single: " << a.with << " and " << b.with;
  }
  EXPECT_TRUE(repair::pair_candidates(*program, singles, distances, 0.4, {40, 4, 3, 3, 0}).empty());
}


namespace {

// The edits of `kind` the search would try on `student` beside the course's specular reference,
// each as its line reads once made.
std::vector<std::string> lines_of_kind(const std::string& student, repair::RepairKind kind) {
  const std::string vertex = glsl_of("specular", shader::Stage::vertex), reference = glsl_of("specular", shader::Stage::fragment);
  std::vector<std::string> out;
  for (const auto& e : repair::program_repair_edits({vertex, student}, {vertex, reference}))
    if (e.kind == kind) out.push_back(repair::edited_line(student, e));
  return out;
}

bool has(const std::vector<std::string>& lines, const std::string& line) { return std::find(lines.begin(), lines.end(), line) != lines.end(); }

// The specular checkpoint with its highlight in a helper function above main, V written as `v_value`.
std::string helpers_program(const std::string& v_value) {
  const std::string reference = glsl_of("specular", shader::Stage::fragment);
  return reference.substr(0, reference.find("void main(void) {")) +
         "vec4 specularTerm(vec3 n, vec3 l, vec3 v) {\n"
         "    vec3 r = reflect(-l, n);\n"
         "    return uSpecularColor * uLightColor * pow(max(dot(v, r), 0.0), 6.0);\n"
         "}\n"
         "void main(void) {\n"
         "    vec3 n = normalize(vNormal);\n"
         "    vec3 l = normalize(uLightPosition - vPosition);\n"
         "    vec3 v = " + v_value + ";\n"
         "    fragColor = uAmbientColor + uDiffuseColor * uLightColor * max(dot(n, l), 0.0) + specularTerm(n, l, v);\n"
         "}\n";
}

// Whether `fragment` (beside the course's specular reference) gets a pair editing its lines into
// `a` and `b`, with no single nearer than the student's own (aligned pairs alone).
bool paired(const std::string& fragment, const std::string& a, const std::string& b) {
  const course::Preset& specular = *course::builtin_course().preset("specular");
  const repair::CandidateCounts counts{128, 16, 0, 0, 128};
  const auto program = repair::repair_program(specular.vertex, {"phong_frag.glsl", fragment}, specular.vertex, specular.fragment, {});
  if (!program) return false;
  const auto singles = repair::single_candidates(*program, counts);
  for (const auto& pair : repair::pair_candidates(*program, singles, std::vector<double>(singles.size(), 0.5), 0.5, counts)) {
    std::set<std::string> lines;
    for (const auto& e : pair.edits) lines.insert(repair::edited_line(program->fragment.source.glsl, e));
    if (lines.contains(a) && lines.contains(b)) return true;
  }
  return false;
}

}  // namespace

// What a student written in their own shape left out is put back at the line they left it out of,
// in their names (repair/left_out_edits.h): the tutorial's program with each thing left out in turn.
// A program that leaves nothing out gets none of these edits.
TEST(LeftOutEditsTest, WhatAStudentLeftOutIsPutBackAtTheirLineInTheirNames) {
  using K = repair::RepairKind;
  const std::string reference = glsl_of("specular", shader::Stage::fragment);
  const std::string tutorial = testkit::with_tutorial_main(reference);
  for (const K kind : {K::factor_added, K::term_added, K::exponent_added, K::guard_added, K::value_added, K::swizzle_removed})
    for (const std::string& right : {reference, tutorial})
      for (const auto& line : lines_of_kind(right, kind)) ADD_FAILURE() << "a right program gets " << line;

  EXPECT_TRUE(has(lines_of_kind(typed(tutorial, "diff * uDiffuseColor * uLightColor", "diff * uDiffuseColor"), K::factor_added),
                  "vec4 color = uAmbientColor + diff * uDiffuseColor * uLightColor;"));
  EXPECT_TRUE(has(lines_of_kind(typed(tutorial, "uAmbientColor + diff", "diff"), K::term_added),
                  "vec4 color = uAmbientColor + diff * uDiffuseColor * uLightColor;"));
  EXPECT_TRUE(has(lines_of_kind(typed(tutorial, "pow(max(dot(viewDir, reflectDir), 0.0), 6.0)", "max(dot(viewDir, reflectDir), 0.0)"),
                                K::exponent_added),
                  "float spec = pow(max(dot(viewDir, reflectDir), 0.0), 6.0);"))
      << "the exponent the reference declares, as the number it declares it with";
  EXPECT_TRUE(has(lines_of_kind(typed(tutorial, "if (diff > 0.0) {", "{"), K::guard_added), "if (dot(norm, lightDir) > 0.0) {"))
      << "the reference's NdotL > 0.0, its NdotL as the dot product it is, in the student's names";
  EXPECT_TRUE(has(lines_of_kind(typed(tutorial, "        color += spec * uSpecularColor * uLightColor;\n", ""), K::value_added),
                  "float spec = pow(max(dot(viewDir, reflectDir), 0.0), 6.0); color += uSpecularColor * uLightColor * spec;"));
  EXPECT_TRUE(has(lines_of_kind(typed(tutorial, "fragColor = color;", "fragColor = color.bgra;"), K::swizzle_removed), "fragColor = color;"));
  // The clamp left out of a line that reads as the reference's `float NdotL = dot(N, L);`: the
  // student reads it where the reference reads max(0.0, NdotL), so the clamp goes where they wrote it.
  EXPECT_TRUE(has(lines_of_kind(typed(tutorial, "max(dot(norm, lightDir), 0.0)", "dot(norm, lightDir)"), K::clamped),
                  "float diff = max(0.0, dot(norm, lightDir));"));
  // The guard of a helper: an early return before its first statement that reads a parameter.
  const std::string helper = helpers_program("normalize(-vPosition)");
  EXPECT_TRUE(has(lines_of_kind(helper, K::guard_added), "if (!(dot(n, l) > 0.0)) { return vec4(0.0); } vec3 r = reflect(-l, n);"));
  // The helper never called: added to the colour, with main's locals of its parameters' names.
  EXPECT_TRUE(has(lines_of_kind(typed(helper, " + specularTerm(n, l, v);", ";"), K::value_added),
                  "fragColor = uAmbientColor + uDiffuseColor * uLightColor * max(dot(n, l), 0.0); fragColor += specularTerm(n, l, v);"));

  // Said in the homework's terms, with the student's names.
  repair::RepairEdit factor;
  factor.kind = K::factor_added;
  factor.subject = "uDiffuseColor";
  factor.other = "uLightColor";
  EXPECT_EQ(repair::repair_words(factor), "`uDiffuseColor` is not multiplied by `uLightColor`, as the homework's formula multiplies it");
  repair::RepairEdit guard;
  guard.kind = K::guard_added;
  guard.subject = "spec";
  guard.other = "dot(norm, lightDir) > 0.0";
  EXPECT_EQ(repair::repair_words(guard),
            "`spec` gets the highlight where the surface faces away from the light too: the homework adds it only where "
            "`dot(norm, lightDir) > 0.0`");
}

// Each term in a local of its own and the guard by step() (a shape the rules were not written
// beside: bench/shapes/specular.py's held-out step guard): what is left out is put back at the
// student's line, a declaration's guard as a conditional value (a declaration cannot go inside an
// `if`), the clamp on the student's copy of N.L, an unread term added to the colour.
TEST(LeftOutEditsTest, TermsInLocalsOfTheirOwnGetWhatWasLeftOutBack) {
  using K = repair::RepairKind;
  const std::string reference = glsl_of("specular", shader::Stage::fragment);
  const std::string step = reference.substr(0, reference.find("void main(void) {")) +
                           "void main(void) {\n"
                           "    vec3 normal = normalize(vNormal);\n"
                           "    vec3 toLight = normalize(uLightPosition - vPosition);\n"
                           "    vec3 toEye = normalize(-vPosition);\n"
                           "    vec3 mirrored = reflect(-toLight, normal);\n"
                           "    float cosTheta = dot(normal, toLight);\n"
                           "    float kd = max(cosTheta, 0.0);\n"
                           "    float ks = step(0.0, cosTheta) * pow(max(dot(mirrored, toEye), 0.0), 6.0);\n"
                           "    vec4 ambient = uAmbientColor;\n"
                           "    vec4 diffuse = kd * uDiffuseColor * uLightColor;\n"
                           "    vec4 specular = ks * uSpecularColor * uLightColor;\n"
                           "    fragColor = ambient + diffuse + specular;\n"
                           "}\n";
  EXPECT_TRUE(has(lines_of_kind(typed(step, "step(0.0, cosTheta) * pow", "pow"), K::guard_added),
                  "float ks = cosTheta > 0.0 ? pow(max(dot(mirrored, toEye), 0.0), 6.0) : 0.0;"));
  EXPECT_TRUE(has(lines_of_kind(typed(step, "float kd = max(cosTheta, 0.0);", "float kd = cosTheta;"), K::clamped), "float kd = max(0.0, cosTheta);"));
  EXPECT_TRUE(has(lines_of_kind(typed(step, "fragColor = ambient + ", "fragColor = "), K::value_added),
                  "fragColor = diffuse + specular; fragColor += ambient;"));
  EXPECT_TRUE(has(lines_of_kind(typed(step, " + specular;", ";"), K::value_added), "fragColor = ambient + diffuse; fragColor += specular;"));
  // Both left out of the sum: each added after the same write, paired.
  EXPECT_TRUE(paired(typed(step, "fragColor = ambient + diffuse + specular;", "fragColor = diffuse;"), "fragColor = diffuse; fragColor += ambient;",
                     "fragColor = diffuse; fragColor += specular;"));
  for (const K kind : {K::clamped, K::value_added}) EXPECT_TRUE(lines_of_kind(step, kind).empty()) << "nothing is left out of it";
}

// Two things left out, each at a line aligned by what it lacks, are paired before any nearest
// single is: the clamp at a line that reads as the reference's `float NdotL = dot(N, L);` (the
// student reads it where the reference reads it clamped) and the light's colour left out of the
// specular term, in the coefficients shape (`coeffDiffuse`, += accumulation).
TEST(LeftOutEditsTest, TwoThingsLeftOutArePairedAsAlignedEdits) {
  const std::string reference = glsl_of("specular", shader::Stage::fragment);
  const std::string student = reference.substr(0, reference.find("void main(void) {")) +
                              "void main(void) {\n"
                              "    vec3 N = normalize(vNormal);\n"
                              "    vec3 L = normalize(uLightPosition - vPosition);\n"
                              "    vec3 V = normalize(-vPosition);\n"
                              "    vec3 R = -reflect(L, N);\n"
                              "    float coeffDiffuse = dot(N, L);\n"
                              "    float coeffSpecular = 0.0;\n"
                              "    if (coeffDiffuse > 0.0) {\n"
                              "        coeffSpecular = pow(max(dot(R, V), 0.0), 6.0);\n"
                              "    }\n"
                              "    fragColor = uAmbientColor;\n"
                              "    fragColor += coeffDiffuse * uDiffuseColor * uLightColor;\n"
                              "    fragColor += coeffSpecular * uSpecularColor;\n"
                              "}\n";
  EXPECT_TRUE(paired(student, "float coeffDiffuse = max(0.0, dot(N, L));", "fragColor += coeffSpecular * uSpecularColor * uLightColor;"));

  // The exponent left out and its number changed: the changed line is dead until the power reads
  // it again, so the power put back is paired with the edits of dead lines.
  std::string no_power = student;
  const auto swap = [&](const std::string& from, const std::string& to) { no_power = typed(no_power, from, to); };
  swap("    vec3 N = normalize(vNormal);\n", "    float specularAlpha = 16.0;\n    vec3 N = normalize(vNormal);\n");
  swap("float coeffDiffuse = dot(N, L);", "float coeffDiffuse = max(dot(N, L), 0.0);");
  swap("pow(max(dot(R, V), 0.0), 6.0)", "max(dot(R, V), 0.0)");
  swap("coeffSpecular * uSpecularColor;", "coeffSpecular * uSpecularColor * uLightColor;");
  const std::string powered = "coeffSpecular = pow(max(dot(R, V), 0.0), specularAlpha);";
  EXPECT_TRUE(paired(no_power, "float specularAlpha = 6.0;", powered));

  // The exponent and the whole specular term left out: the unread `max(dot(R, V), 0.0)` is the
  // specular term's `max` (it reads R and V), not the diffuse term's, so the term added is the
  // specular colour's, and it is paired with the power put back.
  std::string no_term = typed(no_power, "    float specularAlpha = 16.0;\n", "    float specularAlpha = 6.0;\n");
  no_term = typed(no_term, "    fragColor += coeffSpecular * uSpecularColor * uLightColor;\n", "");
  const std::string diffuse = "fragColor += coeffDiffuse * uDiffuseColor * uLightColor;";
  const std::string added = diffuse + " fragColor += uSpecularColor * uLightColor * coeffSpecular;";
  const auto value_lines = lines_of_kind(no_term, repair::RepairKind::value_added);
  EXPECT_TRUE(has(value_lines, added));
  EXPECT_FALSE(has(value_lines, diffuse + " fragColor += uDiffuseColor * uLightColor * coeffSpecular;"));
  EXPECT_TRUE(paired(no_term, added, powered));
}

// A local each program leaves unaligned, one of a type on each side, is aligned: the half vector
// written into the tutorial's reflectDir gets the reference's R back in the student's names.
TEST(LeftOutEditsTest, TheOneLocalEachLeavesUnalignedIsRestoredInTheStudentsNames) {
  const std::string tutorial = testkit::with_tutorial_main(glsl_of("specular", shader::Stage::fragment));
  const auto restored = lines_of_kind(typed(tutorial, "reflect(-lightDir, norm)", "normalize(lightDir + viewDir)"), repair::RepairKind::value_restored);
  EXPECT_TRUE(has(restored, "vec3 reflectDir = reflect(-lightDir, norm);"));

  // A helper written above main declares its r from l and n before main's lines align them: the
  // names are aligned again until no more align, so r is R and V, computed as L, is the one left.
  const std::string reference = glsl_of("specular", shader::Stage::fragment);
  const std::string helpers = helpers_program("l");
  EXPECT_TRUE(has(lines_of_kind(helpers, repair::RepairKind::value_restored), "vec3 v = normalize(-vPosition);"));

  // A local aligned by its uses alone (l, not normalised, is L where it is read) aligns the
  // declarations that read it (r is R), so V, from the eye, is the one left and gets its value back
  // as the reference writes it: a candidate that reads as the reference, paired early.
  const std::string two_wrong = reference.substr(0, reference.find("void main(void) {")) +
                                "void main(void) {\n"
                                "    vec3 n = normalize(vNormal);\n"
                                "    vec3 l = uLightPosition - vPosition;\n"
                                "    vec3 v = normalize(vPosition);\n"
                                "    vec3 r = reflect(-l, n);\n"
                                "    float lambert = max(dot(n, l), 0.0);\n"
                                "    float phong = max(sign(dot(n, l)), 0.0) * pow(max(dot(v, r), 0.0), 6.0);\n"
                                "    fragColor = uAmbientColor + lambert * uDiffuseColor * uLightColor + phong * uSpecularColor * uLightColor;\n"
                                "}\n";
  const std::string vertex = glsl_of("specular", shader::Stage::vertex);
  bool restored_as_the_reference = false;
  for (const auto& e : repair::program_repair_edits({vertex, two_wrong}, {vertex, reference}))
    if (e.kind == repair::RepairKind::value_restored && repair::edited_line(two_wrong, e) == "vec3 v = normalize(-vPosition);")
      restored_as_the_reference = e.reads_as_reference;
  EXPECT_TRUE(restored_as_the_reference);
}

// A hostile stage is not read past the search's budget: finding edits grows with the square of a
// stage's length (a 64 KB stage of one-line statements listed 700,000 edits in 3.7 s of the
// server's own time), so a stage over kRepairTokensAStage gets no search and the report says why;
// one within it is read, and a classmate's stage over it is passed over.
TEST(RepairSearchTest, AStageBeyondTheSearchsTokenBudgetIsNotReadAndTheReportSaysWhy) {
  const course::Course& c = course::builtin_course();
  const course::Preset* specular = c.preset("specular");
  ASSERT_NE(specular, nullptr);
  const std::string reference = glsl_of("specular", shader::Stage::fragment);
  const std::string head = reference.substr(0, reference.find("void main(void) {"));
  // Each line 19 tokens: a local read once more, as the edits that swap names multiply.
  const auto stage_of = [&](size_t lines) {
    std::string body = "void main(void) {\n  vec3 N = normalize(vNormal);\n  fragColor = vec4(0.0);\n";
    for (size_t i = 0; i < lines; ++i) body += "  float c" + std::to_string(i) + " = dot(N, N); fragColor += vec4(c" + std::to_string(i) + ");\n";
    return shader::ShaderFile{"hostile_frag.glsl", head + body + "}\n"};
  };
  const shader::ShaderFile within = stage_of(150), beyond = stage_of(1200);
  const auto read = repair::repair_program(specular->vertex, within, specular->vertex, specular->fragment, {{specular->vertex, beyond}});
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_TRUE(read->classmates.empty()) << "a classmate's stage over the budget is passed over";
  const auto refused = repair::repair_program(specular->vertex, beyond, specular->vertex, specular->fragment, {});
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::payload_too_large);
  EXPECT_NE(refused.error().message.find("the fragment stage holds"), std::string::npos) << refused.error().message;

  // Through the road: the grade's report says why no search ran, and none did.
  worker::PoolConfig config;
  config.workers = 1;
  config.executable = SHADELAB_CLI;
  config.warm_up = worker::WarmUp::none;
  worker::WorkerPool pool(config);
  worker::Job job = worker::course_job(c, worker::JobKind::grade, specular->vertex, beyond);
  job.grade.reference_vertex = specular->vertex;
  job.grade.reference_fragment = specular->fragment;
  grade::Report report;
  road::search_repair(pool, job, "", repair::RepairShown::repaired_line, {}, report);
  EXPECT_FALSE(report.repair_search.has_value());
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("no repair was searched for: the fragment stage holds"), std::string::npos) << report.warnings[0];
}
