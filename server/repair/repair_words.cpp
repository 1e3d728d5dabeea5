#include "repair/repair_words.h"

namespace shadelab::repair {

namespace {

// A value the same everywhere where the homework's varies: at every point of the fragment stage,
// for every vertex of the vertex stage.
std::string same_everywhere(const RepairEdit& e) {
  const bool vertex = e.stage == shader::Stage::vertex;
  const std::string same = vertex ? " is the same for every vertex, where the homework" : " is the same at every point, where the homework";
  if (e.other.empty()) return same + (vertex ? "'s changes from vertex to vertex" : "'s changes from point to point");
  return same + (vertex ? " computes it for each vertex from " : " computes it at each point from ") + e.other;
}

}  // namespace

std::string repair_words(const RepairEdit& e, std::string_view meaning) {
  // The subject, and where the course names what it is, that too: "`toEye`, the direction to the eye,".
  const std::string name = "`" + e.subject + "`", x = meaning.empty() ? name : name + ", " + std::string(meaning) + ",";
  switch (e.said_as.value_or(e.kind)) {
    case RepairKind::normalised: return name + " is not normalised: " + (meaning.empty() ? "a direction" : std::string(meaning)) + " must be a unit vector";
    case RepairKind::unnormalised: return x + " is normalised where the homework uses its length as it is";
    case RepairKind::clamped: return x + " is not clamped at 0: a cosine below 0 must count as 0, max(0.0, ...)";
    case RepairKind::factor_added: return x + " is not multiplied by `" + e.other + "`, as the homework's formula multiplies it";
    case RepairKind::term_added: return x + " is never added: the homework's colour adds it to the other terms";
    case RepairKind::exponent_added: return x + " is not raised to the exponent `" + e.other + "`: the highlight is this cosine to the power alpha";
    case RepairKind::value_added:
      return x + " is computed and never used: the homework adds `" + e.other + "` to the colour";
    case RepairKind::swizzle_removed: return x + " reorders the colour's channels: the homework uses them in order, red, green, blue";
    case RepairKind::guard_added:
      return x + " gets the highlight where the surface faces away from the light too: the homework adds it only where `" + e.other + "`";
    case RepairKind::direction_w: {
      const std::string by = e.homework_matrix.empty() ? "" : " (the homework transforms it by `" + e.homework_matrix + "`)";
      return e.other == "0.0" ? x + " is a direction, so its w must be 0: with w = 1 the matrix's translation moves it" + by
                              : x + " is a point, so its w must be 1: with w = 0 the matrix's translation is lost" + by;
    }
    case RepairKind::negation_removed:
    case RepairKind::negation_added: return x + " has the wrong sign";
    case RepairKind::operator_swapped:
      return e.other == "-" ? x + " is added where the homework subtracts it" : x + " is subtracted where the homework adds it";
    case RepairKind::matrix_added: return x + " is not transformed by `" + e.other + "`";
    case RepairKind::factor_removed:
      if (!e.other.empty()) return "`" + e.other + "` is multiplied by " + name + " here: the homework uses `" + e.other + "` as it is";
      return x + " should not multiply here: the homework uses the value as it is";
    case RepairKind::term_removed: return x + " should not be there: it moves the value away from the homework's";
    case RepairKind::name_replaced: return x + " is not the value the homework uses here";
    case RepairKind::literal_refit: return x + " is not the number the homework uses here";
    case RepairKind::arguments_swapped: return x + " has its arguments the wrong way round";
    case RepairKind::flat_removed:
      return x + " is declared `flat`: each triangle gets one value, where the homework interpolates it across the triangle (remove "
                 "`flat` here and where the fragment stage declares " + name + ")";
    case RepairKind::statement_restored:
      if (e.stage == shader::Stage::fragment) return x + " is never written: the colour the fragment stage draws is what it writes there";
      if (e.subject == "gl_Position") return x + " is never written: the vertex stage must say where each vertex lands";
      return x + " is never written: the fragment stage reads what the vertex stage writes there";
    case RepairKind::write_restored:
      return x + " misses a statement the homework has here: it writes " + name + " once more than yours does";
    case RepairKind::value_restored:
      if (e.constant_value) return x + same_everywhere(e);
      return x + " is not computed as the homework computes it";
    case RepairKind::condition_restored: return "the condition " + x + " is not the one the homework tests here";
  }
  return x + " differs from the homework";
}

std::string repair_label(const RepairEdit& e, std::string_view symbol) {
  const std::string s = symbol.empty() ? "`" + e.subject + "`" : std::string(symbol);
  switch (e.said_as.value_or(e.kind)) {
    case RepairKind::normalised: return s + " not normalised";
    case RepairKind::unnormalised: return s + " normalised where the homework uses its length";
    case RepairKind::clamped: return s + " not clamped at 0";
    case RepairKind::factor_added: return s + " not multiplied by `" + e.other + "`";
    case RepairKind::term_added: return s + " never added";
    // Alike for every student who made the mistake, whatever they named their values.
    case RepairKind::exponent_added: return "the cosine not raised to the exponent";
    case RepairKind::guard_added: return "the highlight not guarded by N.L > 0";
    case RepairKind::value_added: return "a term computed and never added to the colour";
    case RepairKind::swizzle_removed: return "the colour's channels reordered";
    case RepairKind::direction_w: return s + (e.other == "0.0" ? " transformed as a point (w = 1)" : " transformed as a direction (w = 0)");
    case RepairKind::negation_removed:
    case RepairKind::negation_added: return s + " with the wrong sign";
    case RepairKind::operator_swapped: return s + (e.other == "-" ? " added where the homework subtracts it" : " subtracted where the homework adds it");
    case RepairKind::matrix_added: return s + " not transformed by `" + e.other + "`";
    case RepairKind::factor_removed: return e.other.empty() ? s + " multiplies where it should not" : "`" + e.other + "` scaled by a number";
    case RepairKind::term_removed: return s + " added where it should not be";
    case RepairKind::name_replaced: return s + " in place of another value";
    case RepairKind::literal_refit: return s + " not the homework's number";
    case RepairKind::arguments_swapped: return s + " with its arguments swapped";
    case RepairKind::flat_removed: return s + " declared flat";
    case RepairKind::statement_restored: return s + " never written";
    case RepairKind::write_restored: return s + " written once less than the homework writes it";
    case RepairKind::value_restored:
      if (!e.constant_value) return s + " computed otherwise";
      return s + (e.stage == shader::Stage::vertex ? " the same for every vertex" : " the same at every point");
    case RepairKind::condition_restored: return "the condition " + s + " not the homework's";
  }
  return s + " differs from the homework";
}

}  // namespace shadelab::repair
