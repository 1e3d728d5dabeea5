#pragma once
// The repair edits a class offers (docs/grading.md, "Repairs", "A class's programs"): the student's
// program read beside classmates' programs that pass the same checkpoint, as it is read beside the
// course's reference (repair/reference_edits.h). A student who names and orders their program as
// classmates do, and not as the reference does (`lightDir`, `reflectDir`, `spec` where the
// reference writes L and R), has values a classmate computes under the same name, where the
// reference computes none: aligning with several correct programs, not one (Clara, PLDI 2018).
//
// Only edits that read another program: a number refit to one a classmate writes, a statement, a
// write, a value or a condition put back. A restored one is a classmate's text, so it is named and
// never shown (repair::writes_reference_text): a repaired line anyone reads is the student's own
// line edited, never a line copied from another student's program.
#include <vector>

#include "repair/repair_edits.h"

namespace shadelab::repair {

// The `count` programs of `classmates` nearest the student's: most of the student's lines written
// alike (spaces aside), ties in the order given (a batch gives them by student name).
// Programs alike to the byte count once.
std::vector<StagePair> nearest_classmates(const ProgramReading& student, const std::vector<StagePair>& classmates, size_t count);

// The edits `classmates` offer that the course's reference does not, each where the student's
// program could be its line (not a dead statement, not a line the student wrote as the reference
// writes it) and could compile (it names no local of the classmate's the student's stage never
// mentions), marked `reads_as_reference` by the course's reference, smallest first. `student` is
// the student's program read beside the course's reference; `reference_edits` are what the
// reference offers already (program_edits(student).live): a caller that tries those too reads
// them once.
std::vector<RepairEdit> classmate_edits(const ProgramReading& student, const std::vector<RepairEdit>& reference_edits,
                                        const std::vector<StagePair>& classmates);
std::vector<RepairEdit> classmate_edits(const StagePair& student, const StagePair& reference, const std::vector<StagePair>& classmates);

}  // namespace shadelab::repair
