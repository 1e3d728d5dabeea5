#pragma once
// One repair edit (docs/grading.md, "Repairs"): what it does, the span of one stage's GLSL it
// replaces, and how it is shown. The edits found in a program are repair/repair_edits.h's; the
// kinds, with what each reads and says, are repair/repair_kind.h's.
#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>

#include "core/enum_names.h"
#include "repair/repair_kind.h"
#include "shader/shader_source.h"

namespace shadelab::repair {

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

// "Smaller": an edit whose line then reads as the reference's first, then fewer nodes, then the
// kind's order (repair/repair_kind.h), then the vertex stage before the fragment, then the place
// in the stage.
inline bool smaller(const RepairEdit& a, const RepairEdit& b) {
  return std::tuple(!a.reads_as_reference, a.nodes, a.kind, a.stage, a.begin) <
         std::tuple(!b.reads_as_reference, b.nodes, b.kind, b.stage, b.begin);
}

// A program's two stages as the driver gets them.
struct StagePair {
  std::string_view vertex, fragment;
};

}  // namespace shadelab::repair
