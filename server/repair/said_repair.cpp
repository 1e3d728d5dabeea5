#include "repair/said_repair.h"

#include "repair/aligned_lines.h"
#include "repair/repair_words.h"
#include "shader/glsl_lines.h"

namespace shadelab::repair {

namespace {

// Which of the homework formula's `vectors` the edit's subject is, where it is a local of the
// student's fragment stage that stands for one of the reference fragment stage's (by the student's
// own name or the one aligned with it): the formula's name for it ("L") and its words; none else.
const VectorWords::value_type* vector_of(const RepairProgram& p, const RepairEdit& e, const VectorWords& vectors) {
  if (vectors.empty() || e.stage != shader::Stage::fragment || p.reference_fragment.empty()) return nullptr;
  const std::string& glsl = p.fragment.source.glsl;
  const std::string name = AlignedLines(glsl, p.reference_fragment).reference_name(e.subject, edited_line(glsl, e));
  const auto found = vectors.find(name);
  return found == vectors.end() ? nullptr : &*found;
}

SaidEdit said_edit(const RepairProgram& p, const RepairEdit& e, RepairShown shown, const VectorWords& vectors) {
  const StudentStage& stage = p[e.stage];
  const auto* vector = vector_of(p, e, vectors);
  SaidEdit out{e.kind, e.stage, std::nullopt, std::nullopt, repair_words(e, vector ? std::string_view(vector->second) : ""),
               std::nullopt, repair_label(e, vector ? std::string_view(vector->first) : ""),
               std::string(shader::line_of(stage.source.glsl, e.line))};
  if (shown != RepairShown::what) {
    out.file = stage.file->name.empty() ? std::string(to_string(e.stage)) : stage.file->name;
    out.line = stage.source.locate(e.line, 0).file_line;
  }
  // A restored statement or value is the reference's text, not the student's line: named, never shown.
  if (shown == RepairShown::repaired_line && !writes_reference_text(e.kind)) out.repaired_line = edited_line(stage.source.glsl, e);
  return out;
}

}  // namespace

std::vector<SaidEdit> said_repair(const RepairProgram& p, const std::vector<RepairEdit>& edits, RepairShown shown, const VectorWords& vectors) {
  std::vector<SaidEdit> out;
  for (const auto& e : edits) out.push_back(said_edit(p, e, shown, vectors));
  return out;
}

}  // namespace shadelab::repair
