#pragma once
// A confirmed repair as the engine says it, edit by edit: where (the student's file and line, as
// far as the course shows), what is wrong in the homework's words, the label a class is counted
// by, and the repaired line for whoever may see it. grade/repair_statement.h puts it in a report.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "repair/repair_candidates.h"

namespace shadelab::repair {

// The reference's locals that are the homework formula's vectors, each with its words: "V": "the
// direction to the eye" (grade::VectorWords, a checkpoint's).
using VectorWords = std::map<std::string, std::string, std::less<>>;

struct SaidEdit {
  RepairKind kind = RepairKind::normalised;
  shader::Stage stage = shader::Stage::fragment;
  std::optional<std::string> file;  // none where the course shows only what is wrong
  std::optional<int> line;          // the file's line, 1-based
  std::string text;                 // "`L` is not normalised: the direction to the light must be a unit vector"
  std::optional<std::string> repaired_line;
  std::string label;                // "L not normalised"
  std::string student_line;         // the line the edit changes, as the student wrote it (never shown)
};

// Each of `edits` of `p` said as far as `shown` allows; a subject that stands for one of the
// formula's `vectors` said in its words and counted by its symbol.
std::vector<SaidEdit> said_repair(const RepairProgram& p, const std::vector<RepairEdit>& edits, RepairShown shown, const VectorWords& vectors);

}  // namespace shadelab::repair
