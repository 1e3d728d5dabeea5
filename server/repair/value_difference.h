#pragma once
// What a restored value changes, said in the homework's words. A value the search restores
// (RepairKind::value_restored) is the reference's text: it is named, never shown. Where the
// student's value and the reference's differ by one change a student makes (a normalize left
// out, a sign, a max(0.0, ...) missing, one name or number for another), the confirmed repair is
// that change, and its words say so ("`L` is not normalised") instead of "not computed as the
// homework computes it". Where they differ by more, nothing is claimed: the general words stay.
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "repair/repair_edit.h"
#include "shader/glsl_lines.h"

namespace shadelab::repair {

// The words of a restored value: the kind whose words say the change, and what they name. Every
// name in `subject` is the student's own text; `other` only a new operator or, for a matrix, the
// uniform the student's program declares.
struct ValueDifference {
  RepairKind said_as = RepairKind::value_restored;
  std::string subject;
  std::string other;
  // direction_w, where the student's matrix differs too: the matrix the homework's value is
  // transformed by (`uMeshToWorldRotMatrix` for a normal the student moves with the mesh).
  std::string homework_matrix;
};

// The one change that turns the student's value of `name` (their tokens) into the reference's,
// or none when the two differ by more than one recognisable change.
std::optional<ValueDifference> value_difference(std::span<const shader::GlslToken> student,
                                                std::span<const shader::GlslToken> reference, std::string_view name);

}  // namespace shadelab::repair
