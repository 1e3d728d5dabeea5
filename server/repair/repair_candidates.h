#pragma once
// What a repair search tries, in its order (docs/grading.md, "Repairs"): a failing program's
// single edits (the class's where a class batch gives its passing programs, the student's own,
// those that read the reference), then, where no single one repairs it, pairs of them. Decided
// from tokens alone; whether a candidate repairs anything only a render says, and the road runs
// those (road/repair_search.h).
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/expected.h"
#include "repair/repair_edits.h"
#include "repair/value_probes.h"
#include "shader/shader_source.h"

namespace shadelab::repair {

// Another program that passes the same checkpoint: a classmate's, read beside the student's in a
// class batch's second search.
struct PassingProgram {
  shader::ShaderFile vertex, fragment;
};

// One stage of the student's program as the driver gets it, and the file it came from.
struct StudentStage {
  const shader::ShaderFile* file = nullptr;
  shader::UnwrappedSource source;
};

// The program a search edits, and what it is read beside.
struct RepairProgram {
  StudentStage vertex, fragment;
  // The student's program read once beside the grade's reference (beside nothing where the grade
  // has none): every finder and the words read it, none reads the text again.
  ProgramReading read;
  std::vector<std::pair<std::string, std::string>> classmates;  // each passing classmate's GLSL: vertex, fragment
  // The student's program's edits, found once as it is read: the live ones are its singles, the
  // dead ones wait for the pairs that make their line live again.
  ProgramEdits edits;
  const StudentStage& operator[](shader::Stage s) const { return s == shader::Stage::vertex ? vertex : fragment; }
};

// The tokens a stage may hold for the search to read it (each of the student's stages, each
// classmate's). Finding the edits reads a stage's statements against each other, so its time and
// the edits it lists grow with the square of its length: a hostile 64 KB stage of one-line
// statements lists 700,000 edits in 3.7 s of the server's own time. The homework's programs hold
// 200-600 tokens; at this budget the worst seen was 59,983 edits in 0.15 s (2-core Xeon).
inline constexpr size_t kRepairTokensAStage = 4096;

// The student's program (the files the grade draws) read beside the grade's reference and the
// classmates' programs that can be read (unwrapped, within the budget); invalid_argument where a
// stage of the student's cannot be unwrapped, payload_too_large, saying which and by how much,
// where one holds more than kRepairTokensAStage tokens.
Expected<RepairProgram> repair_program(const shader::ShaderFile& vertex, const shader::ShaderFile& fragment,
                                            const shader::ShaderFile& reference_vertex, const shader::ShaderFile& reference_fragment,
                                            const std::vector<PassingProgram>& classmates);

// How many candidates of each kind a search may try (road::RepairBudget counts them).
struct CandidateCounts {
  int own = 0;          // single edits of the student's own program
  int reference = 0;    // single edits that read the reference (repair/reference_edits.h)
  int from_class = 0;   // single edits the class offers, from the `classmates` nearest the student's program
  int classmates = 0;
  int pairs = 0;
};

struct RepairCandidate {
  std::vector<RepairEdit> edits;        // one, or a pair
  shader::ShaderFile vertex, fragment;  // the program with the edits made
  bool from_class = false;              // a single a classmate's program offers (repair/classmate_edits.h)
};

// Whether `e` aligns the student's line with the reference: the line then reads as the
// reference's, or is aligned by what it lacks (a factor, a term, a clamp the reference's
// counterpart reads: repair/left_out_edits.h).
bool aligns(const RepairEdit& e);

// The program with `edits` made, they in turn smallest first: an edited stage given as the GLSL the
// edits made (the same program the driver compiles), the other as the student's file. No edits:
// the student's own.
RepairCandidate candidate_of(const RepairProgram& p, std::vector<RepairEdit> edits);

// The edits the class's programs nearest the student's offer beyond the reference's: none without
// classmates, a reference or a count for them.
std::vector<RepairEdit> class_edits(const RepairProgram& p, const CandidateCounts& counts);

// The single edits, in the order they are tried: the first `from_class` the class offers, then,
// smallest first, the first `own` of the student's own and the first `reference` of those that
// read the reference. The class's come first because a class is given only to a second search,
// once the same program's first one confirmed none of the others: screened again they would fail
// again, and could spend the confirmations again.
std::vector<RepairCandidate> single_candidates(const RepairProgram& p, const CandidateCounts& counts);

// Pairs for a program no single edit repairs, at most `counts.pairs`, in this order:
// - two singles the class offers (two of a passing program's values, where the student's program
//   is written as that program is), in the singles' order;
// - a single that puts back a term or a statement, with each edit of a line only that could make
//   live (repair/repair_edits.h, Liveness::dead): a mistake the missing term hid;
// - two singles that each make their line read as the reference's or put back what the student
//   left out (the student's program aligned with the reference at two lines), in the singles' order;
// - the single that drew nearest the reference (`distances`, each single's screen; a mistake of two
//   mended must draw nearer than the student's `own` program) with each other single, in the
//   singles' order. A second mistake's edit need not draw nearer alone: the first mistake's error
//   can hide it.
// No pair twice, and none of two edits that touch.
std::vector<RepairCandidate> pair_candidates(const RepairProgram& p, const std::vector<RepairCandidate>& singles,
                                             const std::vector<double>& distances, double own, const CandidateCounts& counts);

// The lines of the student's fragment stage where the values of `c`'s program (a single: the
// student's with its edit made), read beside the reference's (`values`, grade/value_reading.h),
// still depart from the reference's, less the edit's own line: where a second mistake is, once
// the first one's error no longer hides it from the values (a wrong L makes every value that reads
// it differ, and a specular term that leaves out the light's colour then departs nowhere). Empty
// for a pair, a grade without a reference, or values not read. Each line with the changes its
// value needs (repair/value_change.h).
Departures departing_after(const RepairProgram& p, const RepairCandidate& c, const ValueAgreement& values);

// `nearest` (a single's edit) paired with each of `singles` that edits one of the fragment stage's
// `lines`, in the singles' order, at most `counts.pairs`; none of two edits that touch.
std::vector<RepairCandidate> pairs_with(const RepairProgram& p, const RepairEdit& nearest, const std::vector<RepairCandidate>& singles,
                                        const std::set<int>& lines, const CandidateCounts& counts);

}  // namespace shadelab::repair
