#include "repair/repair_words.h"

namespace shadelab::repair {

namespace {

// The subject, and where the course names what it is, that too: "`toEye`, the direction to the eye,".
Said said_of(const RepairEdit& e, std::string_view meaning, std::string_view symbol) {
  const std::string name = "`" + e.subject + "`";
  return Said{name, meaning.empty() ? name : name + ", " + std::string(meaning) + ",", meaning, symbol.empty() ? name : std::string(symbol),
              e.stage, e.subject, e.other, e.homework_matrix, e.constant_value};
}

// A value restored that amounts to an edit of the student's own is said as that edit.
const RepairKindInfo& said_as(const RepairEdit& e) { return info(e.said_as.value_or(e.kind)); }

}  // namespace

std::string repair_words(const RepairEdit& e, std::string_view meaning) { return said_as(e).words(said_of(e, meaning, {})); }

std::string repair_label(const RepairEdit& e, std::string_view symbol) { return said_as(e).label(said_of(e, {}, symbol)); }

}  // namespace shadelab::repair
