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
#include "repair/stage_tokens.h"

namespace shadelab::repair {

// Every edit of the kinds repair/repair_edit.h lists that applies to one stage (its GLSL as the
// driver gets it), smallest first.
std::vector<RepairEdit> repair_edits(const StageTokens& stage);

// Both stages' edits, smallest first, less those in an assignment that cannot reach what the
// program draws (repair/live_statements.h): the candidates a repair search tries, in its order.
// With the reference's stages (empty: none), the reference's edits too.
// With `Liveness::dead`, only the edits that list leaves out for their statement's being dead:
// a pair's second edit where its first puts back what makes that statement live again (a
// deleted term that read V and R).
enum class Liveness { live, dead };
// Both at once, each smallest first: a search reads the live for its singles and keeps the dead
// for its pairs, finding the edits once.
struct ProgramEdits {
  std::vector<RepairEdit> live, dead;
};
ProgramEdits program_edits(const ProgramTokens& student, const ProgramTokens& reference = {});
std::vector<RepairEdit> program_repair_edits(const ProgramTokens& student, const ProgramTokens& reference = {},
                                             Liveness which = Liveness::live);


// `glsl` with `edit` made.
std::string with_edit(std::string_view glsl, const RepairEdit& edit);

// The line `edit` is on, as it reads after the edit.
std::string edited_line(std::string_view glsl, const RepairEdit& edit);

}  // namespace shadelab::repair
