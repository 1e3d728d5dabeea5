#include "repair/said_repair.h"

namespace shadelab::repair {

namespace {

// The subject, and where the course names what it is, that too: "`toEye`, the direction to the eye,".
// `holds`: the vector of the formula's the subject's value is, where the values said so.
Said said_of(const RepairEdit& e, std::string_view meaning, std::string_view symbol, const VectorWords::value_type* holds = nullptr) {
  const std::string name = "`" + e.subject + "`";
  return Said{name, meaning.empty() ? name : name + ", " + std::string(meaning) + ",", meaning, symbol.empty() ? name : std::string(symbol),
              e.stage, e.subject, e.other, e.homework_matrix, e.constant_value, holds ? std::string_view(holds->second) : "",
              holds ? std::string_view(holds->first) : ""};
}

// A value restored that amounts to an edit of the student's own is said as that edit.
const RepairKindInfo& said_as(const RepairEdit& e) { return info(e.said_as.value_or(e.kind)); }

// Which of the homework formula's `vectors` the edit's subject is, where it is a local of the
// student's fragment stage that stands for one of the reference fragment stage's (by the student's
// own name or the one aligned with it): the formula's name for it ("L") and its words; none else.
// `guessed`: the alignment rests on a guess (repair::AlignedLines::reference_name).
const VectorWords::value_type* vector_of(const RepairProgram& p, const RepairEdit& e, const VectorWords& vectors, bool& guessed) {
  if (vectors.empty() || e.stage != shader::Stage::fragment || p.read.beside_nothing()) return nullptr;
  const StageReading& fragment = p.read.fragment;
  const std::string name = fragment.aligned.reference_name(e.subject, fragment.edited_line(e), &guessed);
  const auto found = vectors.find(name);
  return found == vectors.end() ? nullptr : &*found;
}

// Where a value restored (said as itself) is one of the formula's vectors and the student's value
// is another of them at every pixel drawn: `viewDir` computed as the direction to the light. A
// render drew both; nothing else is said of how it differs.
const VectorWords::value_type* held_vector(const RepairProgram& p, const RepairEdit& e, const VectorWords& vectors,
                                           const ValueAgreement& values, const VectorWords::value_type* vector) {
  if (!vector || e.kind != RepairKind::value_restored || e.said_as || e.constant_value) return nullptr;
  for (const auto& name : values_it_holds(p.read, e, values))
    if (const auto found = vectors.find(name); found != vectors.end()) return &*found;
  return nullptr;
}

SaidEdit said_edit(const RepairProgram& p, const RepairEdit& e, RepairShown shown, const VectorWords& vectors, const ValueAgreement& values) {
  const StudentStage& stage = p[e.stage];
  const StageReading& read = p.read[e.stage];
  bool guessed = false;
  const auto* role = vector_of(p, e, vectors, guessed);
  // A vector aligned by a guess (its order in `dot(a, b)`) is said only where the values show it:
  // a student whose two vectors the grader cannot tell apart by their text is never told one is the other.
  const auto* vector = role && (!guessed || value_stands_for(p.read, e, values, role->first)) ? role : nullptr;
  const auto* holds = held_vector(p, e, vectors, values, role);
  SaidEdit out{e.kind, e.stage, std::nullopt, std::nullopt,
               said_as(e).words(said_of(e, vector ? std::string_view(vector->second) : "", {}, holds)), std::nullopt,
               said_as(e).label(said_of(e, {}, vector ? std::string_view(vector->first) : "", holds)), std::string(read.line_of(e))};
  if (shown != RepairShown::what) {
    out.file = stage.file->name.empty() ? std::string(to_string(e.stage)) : stage.file->name;
    out.line = stage.source.locate(e.line, 0).file_line;
  }
  // A restored statement or value is the reference's text, not the student's line: named, never shown.
  if (shown == RepairShown::repaired_line && !writes_reference_text(e.kind)) out.repaired_line = read.edited_line(e);
  return out;
}

}  // namespace

std::string repair_words(const RepairEdit& e, std::string_view meaning) { return said_as(e).words(said_of(e, meaning, {})); }

std::string repair_label(const RepairEdit& e, std::string_view symbol) { return said_as(e).label(said_of(e, {}, symbol)); }

std::vector<SaidEdit> said_repair(const RepairProgram& p, const std::vector<RepairEdit>& edits, RepairShown shown, const VectorWords& vectors,
                                  const ValueAgreement& values) {
  std::vector<SaidEdit> out;
  for (const auto& e : edits) out.push_back(said_edit(p, e, shown, vectors, values));
  return out;
}

}  // namespace shadelab::repair
