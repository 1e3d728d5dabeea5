#include "grade/repair_statement.h"

#include <algorithm>
#include <optional>
#include <regex>
#include <string>

#include "grade/diagnosis.h"
#include "grade/starter_constants.h"

namespace shadelab::grade {

namespace {

Repair repair_of(repair::SaidEdit said) {
  return Repair{said.kind, std::move(said.file), said.line, std::move(said.text), std::move(said.repaired_line), std::move(said.label)};
}

// Where the grader named a changed starter constant ("your shader's exponent is 20.0; the
// course's starter uses 6.0", the first message: grade/judge_code.h) and `e` refits the number
// that line gives it, that message is the edit's words at its line: said once, not twice.
std::optional<std::string> constant_named(const repair::SaidEdit& e, const std::vector<StarterConstant>& constants,
                                          const std::string& fragment_text, const Report& report) {
  if (e.kind != repair::RepairKind::literal_refit || e.stage != shader::Stage::fragment || report.messages.empty()) return std::nullopt;
  if (report.diagnosis.empty() || report.diagnosis == to_string(Diagnosis::nan)) return std::nullopt;
  const auto changed = changed_starter_constants(constants, fragment_text);
  if (changed.size() != 1) return std::nullopt;  // which message names which constant is not ours to guess
  const std::regex gives("\\b" + changed.front().variable + "\\s*=");
  if (!std::regex_search(e.student_line.begin(), e.student_line.end(), gives)) return std::nullopt;
  const std::string& message = report.messages.front();
  return message.ends_with('.') ? message : message + ".";
}

}  // namespace

void state_repair(std::vector<repair::SaidEdit> edits, const std::vector<StarterConstant>& constants, const std::string& fragment_text,
                  Report& report) {
  std::vector<std::string> said, lines;
  bool constant_said = false;  // the grader's message on a changed constant, now at its line
  for (const auto& e : edits) {
    const auto named = constant_named(e, constants, fragment_text, report);
    constant_said = constant_said || named;
    std::string text = named ? *named : e.text + ".";
    said.push_back((e.line ? *e.file + " line " + std::to_string(*e.line) + ": " : std::string()) + text);
  }
  std::vector<Repair> repairs;
  for (auto& e : edits) repairs.push_back(repair_of(std::move(e)));
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
