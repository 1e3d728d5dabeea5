#include "grade/repair_statement.h"

#include <algorithm>
#include <optional>
#include <regex>
#include <string>

#include "repair/aligned_lines.h"
#include "grade/diagnosis.h"
#include "repair/repair_words.h"
#include "grade/starter_constants.h"
#include "shader/glsl_lines.h"

namespace shadelab::grade {

namespace {

// Which of the homework formula's `vectors` the edit's subject is, where it is a local of the
// student's fragment stage that stands for one of the reference fragment stage's (by the student's
// own name or the one aligned with it): the formula's name for it ("L") and its words; none else.
const VectorWords::value_type* vector_of(const repair::RepairProgram& p, const repair::RepairEdit& e, const VectorWords& vectors) {
  if (vectors.empty() || e.stage != shader::Stage::fragment || p.reference_fragment.empty()) return nullptr;
  const std::string& glsl = p.fragment.source.glsl;
  const std::string name = repair::AlignedLines(glsl, p.reference_fragment).reference_name(e.subject, repair::edited_line(glsl, e));
  const auto found = vectors.find(name);
  return found == vectors.end() ? nullptr : &*found;
}

// One edit of a confirmed repair, said as far as `shown` allows.
Repair repair_of(const repair::RepairProgram& p, const repair::RepairEdit& e, repair::RepairShown shown, const VectorWords& vectors) {
  const repair::StudentStage& stage = p[e.stage];
  const auto* vector = vector_of(p, e, vectors);
  Repair repair{e.kind, std::nullopt, std::nullopt, repair::repair_words(e, vector ? std::string_view(vector->second) : ""),
                std::nullopt, repair::repair_label(e, vector ? std::string_view(vector->first) : "")};
  if (shown != repair::RepairShown::what) {
    repair.file = stage.file->name.empty() ? std::string(to_string(e.stage)) : stage.file->name;
    repair.line = stage.source.locate(e.line, 0).file_line;
  }
  // A restored statement or value is the reference's text, not the student's line: named, never shown.
  if (shown == repair::RepairShown::repaired_line && !repair::writes_reference_text(e.kind)) repair.repaired_line = repair::edited_line(stage.source.glsl, e);
  return repair;
}

// Where the grader named a changed starter constant ("your shader's exponent is 20.0; the
// course's starter uses 6.0", the first message: grade/judge_code.h) and `e` refits the number
// that line gives it, that message is the edit's words at its line: said once, not twice.
std::optional<std::string> constant_named(const repair::RepairProgram& p, const repair::RepairEdit& e, const std::vector<StarterConstant>& constants,
                                          const Report& report) {
  if (e.kind != repair::RepairKind::literal_refit || e.stage != shader::Stage::fragment || report.messages.empty()) return std::nullopt;
  if (report.diagnosis.empty() || report.diagnosis == to_string(Diagnosis::nan)) return std::nullopt;
  const auto changed = changed_starter_constants(constants, p.fragment.file->text);
  if (changed.size() != 1) return std::nullopt;  // which message names which constant is not ours to guess
  const std::regex gives("\\b" + changed.front().variable + "\\s*=");
  const std::string_view line = shader::line_of(p.fragment.source.glsl, e.line);
  if (!std::regex_search(line.begin(), line.end(), gives)) return std::nullopt;
  const std::string& message = report.messages.front();
  return message.ends_with('.') ? message : message + ".";
}

}  // namespace

void state_repair(const repair::RepairProgram& p, const std::vector<repair::RepairEdit>& edits, repair::RepairShown shown, const VectorWords& vectors,
                  const std::vector<StarterConstant>& constants, Report& report) {
  std::vector<Repair> repairs;
  for (const auto& e : edits) repairs.push_back(repair_of(p, e, shown, vectors));
  std::vector<std::string> said, lines;
  bool constant_said = false;  // the grader's message on a changed constant, now at its line
  for (size_t i = 0; i < repairs.size(); ++i) {
    const Repair& r = repairs[i];
    const auto named = constant_named(p, edits[i], constants, report);
    constant_said = constant_said || named;
    std::string text = named ? *named : r.text + ".";
    said.push_back((r.line ? *r.file + " line " + std::to_string(*r.line) + ": " : std::string()) + text);
  }
  // Every edit of the repair is in its sentence: a restored value (the reference's text, never
  // shown) by its line, so that a repair of two edits never reads as one.
  const bool shows_a_line = std::any_of(repairs.begin(), repairs.end(), [](const Repair& r) { return r.repaired_line.has_value(); });
  for (const auto& r : repairs)
    if (shows_a_line)
      lines.push_back(r.repaired_line ? "`" + *r.repaired_line + "`"
                                      : r.file.value_or("") + " line " + std::to_string(r.line.value_or(0)) + " as the homework writes it");
  if (!lines.empty())
    said.push_back("With " + lines.front() + (lines.size() > 1 ? " and " + lines.back() : "") +
                   " the frames match the reference's on every frame and light the grade draws.");
  // The formula's "cannot say why" is superseded by what a render confirmed.
  auto& m = report.messages;
  if (report.explanation && !report.explanation->explained) m.erase(std::remove(m.begin(), m.end(), report.explanation->text), m.end());
  if (constant_said) m.erase(m.begin());
  m.insert(m.begin() + std::min<size_t>(constant_said ? 0 : 1, m.size()), said.begin(), said.end());
  report.repair_search->found = std::move(repairs.front());
  if (repairs.size() > 1) report.repair_search->also = std::move(repairs.back());
}

}  // namespace shadelab::grade
