#pragma once
// The edits a repair search tries on a student's program (docs/grading.md, "Repairs"): each one
// span of one stage's GLSL replaced, the inverse of a mistake a Phong homework is made of (a
// vector not normalised, a cosine not clamped, a direction transformed as a point, a sign, a
// uniform or a matrix mixed up, a term or a factor too many). Reading tokens only: whether an
// edit repairs anything is for a render to say (road/repair_search.h), never for this file.
#include <string>
#include <string_view>
#include <vector>

#include "repair/repair_edit.h"
#include "repair/program_reading.h"

namespace shadelab::repair {

// Every edit of the kinds repair/repair_edit.h lists that applies to one stage (its GLSL as the
// driver gets it), smallest first.
std::vector<RepairEdit> repair_edits(const StageTokens& stage);

// Both stages' edits, smallest first, less those at a line the student wrote as the program beside
// theirs writes it: the candidates a repair search tries, in its order. With the reference beside
// the student's program (not beside nothing), the reference's edits too (repair/reference_edits.h,
// repair/left_out_edits.h). The live ones are a search's singles; the dead, those in an assignment
// that cannot reach what the program draws (repair/live_statements.h), wait for a pair whose first
// edit puts back what makes that statement live again (a deleted term that read V and R).
struct ProgramEdits {
  std::vector<RepairEdit> live, dead;
};
ProgramEdits program_edits(const ProgramReading& student);

// The same, read here from two programs' text: one of the lists.
enum class Liveness { live, dead };
std::vector<RepairEdit> program_repair_edits(const StagePair& student, const StagePair& reference = {}, Liveness which = Liveness::live);

}  // namespace shadelab::repair
