#pragma once
// The repair edits that read the course's reference program beside the student's
// (docs/grading.md, "Repairs"): the student's stage aligned with the reference's by the names
// each statement writes. Like every repair edit, reading tokens only: a render says whether one
// repairs anything.
#include <vector>

#include "repair/repair_edit.h"
#include "repair/stage_tokens.h"

namespace shadelab::repair {

// The edits that read the course's reference program beside the student's (one stage of each):
// a number refit to one the reference writes, an output the student's stage never writes
// restored, a value it computes otherwise than the reference restored. A restored statement or
// value is the reference's text, so it is never shown as a repaired line
// (grade::Repair::repaired_line), only named by what it writes.
std::vector<RepairEdit> reference_edits(const StageTokens& student, const StageTokens& reference);

}  // namespace shadelab::repair
