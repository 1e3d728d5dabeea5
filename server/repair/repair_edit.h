#pragma once
// One repair edit (docs/grading.md, "Repairs"): what it does, the span of one stage's GLSL it
// replaces, and how it is shown. The edits found in a program are repair/repair_edits.h's.
#include <iterator>
#include <optional>
#include <string>
#include <string_view>

#include "core/enum_names.h"
#include "shader/shader_source.h"

namespace shadelab::repair {

// What an edit does, in the order "smallest" breaks its ties (docs/grading.md, "Repairs").
enum class RepairKind {
  normalised,        // vec3 L = X;  ->  vec3 L = normalize(X);
  unnormalised,      // normalize(X)  ->  X
  clamped,           // dot(V, R)  ->  max(0.0, dot(V, R))
  // What a student left out, put back at their own line (repair/left_out_edits.h):
  factor_added,      // uDiffuseColor * max(...)  ->  uDiffuseColor * uLightColor * max(...): a factor the reference multiplies by
  term_added,        // color = D;  ->  color = uAmbientColor + D;  a uniform the reference adds and the student never reads
  exponent_added,    // max(dot(V, R), 0.0)  ->  pow(max(dot(V, R), 0.0), specularAlpha)
  guard_added,       // { ... }  ->  if (dot(N, L) > 0.0) { ... }: the reference's condition, in the student's names
  value_added,       // float spec = pow(...); never read  ->  ...; color += uSpecularColor * uLightColor * spec;  the reference's term
  swizzle_removed,   // color.bgra  ->  color
  direction_w,       // vec4(n, 1.0)  ->  vec4(n, 0.0), and the other way
  negation_removed,  // -X  ->  X
  negation_added,    // reflect(L, N)  ->  reflect(-L, N); vec3 V = X  ->  vec3 V = -X
  operator_swapped,  // A + B  ->  A - B, and the other way (+= and -= too)
  factor_removed,    // 0.5 * uLightPosition  ->  uLightPosition; M * P  ->  P for a matrix M
  term_removed,      // uLightPosition + vec3(0.0, 4.0, 0.0)  ->  uLightPosition
  matrix_added,      // aVertexNormal  ->  uMeshToWorldRotMatrix * aVertexNormal (a matrix uniform)
  literal_refit,     // max(0.5, X)  ->  max(0.0, X): a number the reference never writes, as one it does
  name_replaced,     // uDiffuseColor  ->  uSpecularColor (a uniform, an input or a local of the same type)
  arguments_swapped, // reflect(N, -L)  ->  reflect(-L, N), where the order matters
  flat_removed,      // flat out vec3 vNormal; and flat in vec3 vNormal;  ->  both interpolated (one edit of two stages)
  statement_restored,// an output the stage never writes: the reference's assignment to it, where it stands there
  write_restored,    // color += X; left out, where the stage writes color otherwise alike: the reference's write, where it stands there
  value_restored,    // vec3 R = normalize(L + V);  ->  the reference's value of R, where each writes R alike
  condition_restored,// if (true)  ->  the reference's condition, where the two have as many ifs
};
inline constexpr EnumName<RepairKind> kRepairKindNames[] = {
    {RepairKind::normalised, "normalised"},
    {RepairKind::unnormalised, "unnormalised"},
    {RepairKind::clamped, "clamped"},
    {RepairKind::factor_added, "factor_added"},
    {RepairKind::term_added, "term_added"},
    {RepairKind::exponent_added, "exponent_added"},
    {RepairKind::guard_added, "guard_added"},
    {RepairKind::value_added, "value_added"},
    {RepairKind::swizzle_removed, "swizzle_removed"},
    {RepairKind::direction_w, "direction_w"},
    {RepairKind::negation_removed, "negation_removed"},
    {RepairKind::negation_added, "negation_added"},
    {RepairKind::operator_swapped, "operator_swapped"},
    {RepairKind::factor_removed, "factor_removed"},
    {RepairKind::term_removed, "term_removed"},
    {RepairKind::matrix_added, "matrix_added"},
    {RepairKind::literal_refit, "literal_refit"},
    {RepairKind::name_replaced, "name_replaced"},
    {RepairKind::arguments_swapped, "arguments_swapped"},
    {RepairKind::flat_removed, "flat_removed"},
    {RepairKind::statement_restored, "statement_restored"},
    {RepairKind::write_restored, "write_restored"},
    {RepairKind::value_restored, "value_restored"},
    {RepairKind::condition_restored, "condition_restored"},
};
static_assert(std::size(kRepairKindNames) == static_cast<std::size_t>(RepairKind::condition_restored) + 1, "a kind without its name");

// Whether an edit of this kind writes the reference's own text (a statement or a value restored):
// such an edit is named, never shown as a repaired line.
constexpr bool writes_reference_text(RepairKind kind) {
  return kind == RepairKind::statement_restored || kind == RepairKind::write_restored || kind == RepairKind::value_restored ||
         kind == RepairKind::condition_restored;
}

// Whether an edit of this kind puts back what the student left out, read from the reference's
// formula (repair/left_out_edits.h): the student's line aligned with the reference's by what it
// lacks, as a line that then reads as the reference's is by its tokens.
constexpr bool puts_back(RepairKind kind) {
  return kind == RepairKind::factor_added || kind == RepairKind::term_added || kind == RepairKind::exponent_added ||
         kind == RepairKind::guard_added || kind == RepairKind::value_added;
}

// Whether an edit of this kind reads the reference (repair::reference_edits): the search counts
// these apart from the student's own edits (road::RepairBudget).
constexpr bool reads_reference(RepairKind kind) {
  return kind == RepairKind::literal_refit || puts_back(kind) || writes_reference_text(kind);
}

// How much of a confirmed repair a reader is shown: what is wrong; what and where (the file's
// line); or the repaired line too. A course chooses it for its students (the profile's
// `repairShown`); whoever may see the references is shown the repaired line.
enum class RepairShown { what, where, repaired_line };
inline constexpr EnumName<RepairShown> kRepairShownNames[] = {
    {RepairShown::what, "what"},
    {RepairShown::where, "where"},
    {RepairShown::repaired_line, "repairedLine"},
};

// A span of the other stage an edit changes with its own, as one edit: a varying's interpolation
// qualifier must match in both stages, so its `flat` goes from both or neither.
struct OtherStageSpan {
  size_t begin = 0, end = 0;
  std::string with;
};

struct RepairEdit {
  shader::Stage stage = shader::Stage::fragment;
  RepairKind kind = RepairKind::normalised;
  size_t begin = 0, end = 0;  // the bytes of the stage's GLSL replaced
  std::string with;
  int line = 0;         // the GLSL line `begin` is on (1-based)
  std::string subject;  // what the edit changes, as the student wrote it: "L", "dot(V, R)", "uDiffuseColor"
  std::string other;    // name_replaced: the name put in its place; direction_w: the new w;
                        // operator_swapped: the new operator; matrix_added: the matrix;
                        // literal_refit: the new number; factor_removed: the name a
                        // number scales, where it is one (`uAmbientColor` in 2.0 * uAmbientColor)
  int nodes = 1;        // syntax nodes the edit changes: "smallest" is fewest
  // Whether the edited line reads as a line of the reference's stage (spaces, comments and the
  // student's names for its locals aside: repair/aligned_lines.h): such an edit is tried before any
  // other, as the student's line aligned with the reference's.
  bool reads_as_reference = false;
  // A line that reads as the reference's, edited all the same (repair/left_out_edits.h): the
  // student reads the value it writes where the reference reads its counterpart clamped, or a
  // guard goes in before its statement, which stays as it is.
  bool edits_aligned_line = false;
  std::optional<OtherStageSpan> other_stage;  // flat_removed: the fragment stage's `flat`
  // value_restored: the student's own edit the restored value amounts to, where it is one
  // (repair/value_difference.h); its words are said, with `subject` and `other` set for them.
  std::optional<RepairKind> said_as;
  // said as direction_w, where the student's matrix differs too: the one the homework transforms by.
  std::string homework_matrix;
  // value_restored, where no one change says it: the student's value is the same at every point
  // where the reference's varies (repair/value_variation.h); `other` then names, as words, the
  // stage's inputs the reference's value reads itself ("`vPosition`"), empty where it reads them
  // through its locals alone.
  bool constant_value = false;
};

// A program's two stages as the driver gets them.
struct StagePair {
  std::string_view vertex, fragment;
};

}  // namespace shadelab::repair
