#include "repair/repair_kind.h"

#include <array>
#include <cstddef>


namespace shadelab::repair {

namespace {

using F = Found;

// A value the same everywhere where the homework's varies: at every point of the fragment stage,
// for every vertex of the vertex stage.
std::string same_everywhere(const Said& e) {
  const bool vertex = e.stage == shader::Stage::vertex;
  const std::string same = vertex ? " is the same for every vertex, where the homework" : " is the same at every point, where the homework";
  if (e.other.empty()) return same + (vertex ? "'s changes from vertex to vertex" : "'s changes from point to point");
  return same + (vertex ? " computes it for each vertex from " : " computes it at each point from ") + e.other;
}

std::string direction_w_words(const Said& s) {
  const std::string by = s.homework_matrix.empty() ? "" : " (the homework transforms it by `" + std::string(s.homework_matrix) + "`)";
  return s.other == "0.0" ? s.named + " is a direction, so its w must be 0: with w = 1 the matrix's translation moves it" + by
                          : s.named + " is a point, so its w must be 1: with w = 0 the matrix's translation is lost" + by;
}

std::string statement_restored_words(const Said& s) {
  if (s.stage == shader::Stage::fragment) return s.named + " is never written: the colour the fragment stage draws is what it writes there";
  if (s.subject == "gl_Position") return s.named + " is never written: the vertex stage must say where each vertex lands";
  return s.named + " is never written: the fragment stage reads what the vertex stage writes there";
}

// One row a kind, in the enum's order. A label is alike for every student who made the mistake,
// whatever they named their values: a class batch counts its students by it.
constexpr RepairKindInfo kKinds[] = {
    {RepairKind::normalised, "normalised", F::in_student_text, false, false,
     [](const Said& s) {
       return s.name + " is not normalised: " + (s.meaning.empty() ? "a direction" : std::string(s.meaning)) + " must be a unit vector";
     },
     [](const Said& s) { return s.symbol + " not normalised"; }},
    {RepairKind::unnormalised, "unnormalised", F::in_student_text, false, false,
     [](const Said& s) { return s.named + " is normalised where the homework uses its length as it is"; },
     [](const Said& s) { return s.symbol + " normalised where the homework uses its length"; }},
    {RepairKind::clamped, "clamped", F::in_student_text, false, false,
     [](const Said& s) { return s.named + " is not clamped at 0: a cosine below 0 must count as 0, max(0.0, ...)"; },
     [](const Said& s) { return s.symbol + " not clamped at 0"; }},
    {RepairKind::factor_added, "factor_added", F::formula, false, false,
     [](const Said& s) { return s.named + " is not multiplied by `" + s.other + "`, as the homework's formula multiplies it"; },
     [](const Said& s) { return s.symbol + " not multiplied by `" + s.other + "`"; }},
    {RepairKind::term_added, "term_added", F::formula, false, false,
     [](const Said& s) { return s.named + " is never added: the homework's colour adds it to the other terms"; },
     [](const Said& s) { return s.symbol + " never added"; }},
    {RepairKind::exponent_added, "exponent_added", F::formula, false, true,
     [](const Said& s) { return s.named + " is not raised to the exponent `" + s.other + "`: the highlight is this cosine to the power alpha"; },
     [](const Said&) { return std::string("the cosine not raised to the exponent"); }},
    {RepairKind::guard_added, "guard_added", F::formula, false, false,
     [](const Said& s) {
       return s.named + " gets the highlight where the surface faces away from the light too: the homework adds it only where `" +
              s.other + "`";
     },
     [](const Said&) { return std::string("the highlight not guarded by N.L > 0"); }},
    {RepairKind::value_added, "value_added", F::formula, false, true,
     [](const Said& s) { return s.named + " is computed and never used: the homework adds `" + s.other + "` to the colour"; },
     [](const Said&) { return std::string("a term computed and never added to the colour"); }},
    {RepairKind::swizzle_removed, "swizzle_removed", F::in_student_text, false, false,
     [](const Said& s) { return s.named + " reorders the colour's channels: the homework uses them in order, red, green, blue"; },
     [](const Said&) { return std::string("the colour's channels reordered"); }},
    {RepairKind::direction_w, "direction_w", F::in_student_text, false, false, direction_w_words,
     [](const Said& s) { return s.symbol + (s.other == "0.0" ? " transformed as a point (w = 1)" : " transformed as a direction (w = 0)"); }},
    {RepairKind::negation_removed, "negation_removed", F::in_student_text, false, false,
     [](const Said& s) { return s.named + " has the wrong sign"; }, [](const Said& s) { return s.symbol + " with the wrong sign"; }},
    {RepairKind::negation_added, "negation_added", F::in_student_text, false, false,
     [](const Said& s) { return s.named + " has the wrong sign"; }, [](const Said& s) { return s.symbol + " with the wrong sign"; }},
    {RepairKind::operator_swapped, "operator_swapped", F::in_student_text, false, false,
     [](const Said& s) {
       return s.other == "-" ? s.named + " is added where the homework subtracts it" : s.named + " is subtracted where the homework adds it";
     },
     [](const Said& s) { return s.symbol + (s.other == "-" ? " added where the homework subtracts it" : " subtracted where the homework adds it"); }},
    {RepairKind::factor_removed, "factor_removed", F::in_student_text, false, false,
     [](const Said& s) {
       if (!s.other.empty()) return "`" + s.other + "` is multiplied by " + s.name + " here: the homework uses `" + s.other + "` as it is";
       return s.named + " should not multiply here: the homework uses the value as it is";
     },
     [](const Said& s) { return s.other.empty() ? s.symbol + " multiplies where it should not" : "`" + s.other + "` scaled by a number"; }},
    {RepairKind::term_removed, "term_removed", F::in_student_text, false, false,
     [](const Said& s) { return s.named + " should not be there: it moves the value away from the homework's"; },
     [](const Said& s) { return s.symbol + " added where it should not be"; }},
    {RepairKind::matrix_added, "matrix_added", F::in_student_text, false, false,
     [](const Said& s) { return s.named + " is not transformed by `" + s.other + "`"; },
     [](const Said& s) { return s.symbol + " not transformed by `" + s.other + "`"; }},
    {RepairKind::literal_refit, "literal_refit", F::reference_number, false, false,
     [](const Said& s) { return s.named + " is not the number the homework uses here"; },
     [](const Said& s) { return s.symbol + " not the homework's number"; }},
    {RepairKind::name_replaced, "name_replaced", F::in_student_text, false, false,
     [](const Said& s) { return s.named + " is not the value the homework uses here"; },
     [](const Said& s) { return s.symbol + " in place of another value"; }},
    {RepairKind::arguments_swapped, "arguments_swapped", F::in_student_text, false, false,
     [](const Said& s) { return s.named + " has its arguments the wrong way round"; },
     [](const Said& s) { return s.symbol + " with its arguments swapped"; }},
    {RepairKind::flat_removed, "flat_removed", F::in_student_text, false, false,
     [](const Said& s) {
       return s.named + " is declared `flat`: each triangle gets one value, where the homework interpolates it across the triangle (remove "
                        "`flat` here and where the fragment stage declares " + s.name + ")";
     },
     [](const Said& s) { return s.symbol + " declared flat"; }},
    {RepairKind::statement_restored, "statement_restored", F::reference_text, true, true, statement_restored_words,
     [](const Said& s) { return s.symbol + " never written"; }},
    {RepairKind::write_restored, "write_restored", F::reference_text, true, true,
     [](const Said& s) { return s.named + " misses a statement the homework has here: it writes " + s.name + " once more than yours does"; },
     [](const Said& s) { return s.symbol + " written once less than the homework writes it"; }},
    {RepairKind::value_restored, "value_restored", F::reference_text, false, false,
     [](const Said& s) {
       if (s.constant_value) return s.named + same_everywhere(s);
       if (!s.holds.empty())
         return s.named + " is computed as " + std::string(s.holds) + ": at every point drawn it holds the homework's " + std::string(s.holds_symbol);
       return s.named + " is not computed as the homework computes it";
     },
     [](const Said& s) {
       if (!s.holds_symbol.empty() && !s.constant_value) return s.symbol + " computed as " + std::string(s.holds_symbol);
       if (!s.constant_value) return s.symbol + " computed otherwise";
       return s.symbol + (s.stage == shader::Stage::vertex ? " the same for every vertex" : " the same at every point");
     }},
    {RepairKind::condition_restored, "condition_restored", F::reference_text, false, false,
     [](const Said& s) { return "the condition " + s.named + " is not the one the homework tests here"; },
     [](const Said& s) { return "the condition " + s.symbol + " not the homework's"; }},
};

constexpr bool rows_in_order() {
  for (std::size_t i = 0; i < std::size(kKinds); ++i)
    if (static_cast<std::size_t>(kKinds[i].kind) != i) return false;
  return true;
}
static_assert(std::size(kKinds) == static_cast<std::size_t>(RepairKind::condition_restored) + 1, "a kind without its row");
static_assert(rows_in_order(), "the table's rows are in the enum's order");

}  // namespace

const RepairKindInfo& info(RepairKind kind) { return kKinds[static_cast<std::size_t>(kind)]; }

std::string_view to_string(RepairKind kind) { return info(kind).name; }

std::optional<RepairKind> repair_kind_named(std::string_view name) {
  for (const auto& row : kKinds)
    if (row.name == name) return row.kind;
  return std::nullopt;
}

}  // namespace shadelab::repair
