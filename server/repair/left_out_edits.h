#pragma once
// The repair edits that put back what a student left out (docs/grading.md, "Repairs"): a factor
// the reference multiplies a uniform by (the light's colour), a uniform the reference adds as a
// term of its own (the ambient colour), the exponent it raises a cosine to, the guard it tests
// (N·L > 0), or a float the student computes and never reads, multiplied in where the reference's
// guard would be. Each is the student's own line with one thing added, in the student's names:
// it may be shown, unlike a statement or a value restored whole. The token search's kinds read
// what a line has; these read what the reference's stage has that the student's lacks, so a
// program written in the student's own shape gets the line where it left something out. Tokens
// only: a render says whether one repairs anything.
#include <vector>

#include "repair/repair_edit.h"
#include "repair/stage_tokens.h"

namespace shadelab::repair {

std::vector<RepairEdit> left_out_edits(const StageTokens& student, const StageTokens& reference);

}  // namespace shadelab::repair
