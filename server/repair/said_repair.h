#pragma once
// What a repair says, edit by edit: what is wrong in the homework's words and without the repaired
// text (a student may be shown these), the label a class is counted by, and, for a confirmed
// repair, where (the student's file and line, as far as the course shows) and the repaired line
// for whoever may see the references. grade/repair_statement.h puts it in a report.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "repair/repair_candidates.h"

namespace shadelab::repair {

// "`L` is not normalised: a direction must be a unit vector". `meaning`: what the edit's subject
// is in the homework's formula, where the course names it (grade/formula_vectors.h): "`L` is not
// normalised: the direction to the light must be a unit vector", "`toEye`, the direction to the
// eye, has the wrong sign".
std::string repair_words(const RepairEdit& edit, std::string_view meaning = {});

// The same mistake in a few words, alike for every student who made it, to count a class by:
// "L not normalised" where `symbol` is the formula's name for the edit's subject ("L"), else the
// subject as written ("`uSpecularColor` in place of another value").
std::string repair_label(const RepairEdit& edit, std::string_view symbol = {});

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
// formula's `vectors` said in its words and counted by its symbol. A value restored whose student
// value `values` (the student's grade's, grade/value_reading.h) found to be another of those
// vectors at every pixel drawn says so: "`viewDir`, the direction to the eye, is computed as the
// direction to the light".
std::vector<SaidEdit> said_repair(const RepairProgram& p, const std::vector<RepairEdit>& edits, RepairShown shown, const VectorWords& vectors,
                                  const ValueAgreement& values = {});

}  // namespace shadelab::repair
