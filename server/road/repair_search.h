#pragma once
// The repair search of a failing code grade (docs/grading.md, "Repairs"): the smallest edit of
// the student's own program (repair/repair_edits.h) that makes it draw what the reference draws,
// under every light the grade uses and within its tolerance. What to try is
// repair/repair_candidates.h's, in what order repair/search_order.h's; how a confirmed repair is said, grade/repair_statement.h's; this
// file runs the candidates.
//
// Each candidate is a grade of its own in a worker, killable like any: one that does not pass
// ShadeLab's compile verdict, hangs, crashes or draws NaN fails its own grade and is passed over,
// never the student's grade's failure. Candidates are screened on a small canvas, smallest first;
// a screened pass is rendered again at the grade's own frames, and only that render states a
// repair. The budget is counted, never timed, so the answer is the same on a busy or an idle
// machine and on any GPU; it lives on the road because only the road may run more jobs.
#include <string>
#include <vector>

#include "grade/formula_vectors.h"
#include "repair/repair_candidates.h"
#include "repair/value_probes.h"
#include "grade/report.h"
#include "worker/job.h"
#include "worker/pool.h"

namespace shadelab::road {

struct RepairBudget {
  int candidates = 128;   // single edits of the student's own program screened, at most
  // Single edits that read the reference (a number refit, a statement or a value restored:
  // repair/reference_edits.h), at most: counted apart, as they are few and come last by size.
  int reference_candidates = 16;
  // Where no single edit repairs the program: the single that drew nearest the reference, paired
  // with each other single in order, at most `pairs` pairs.
  int pairs = 128;
  int confirmations = 2;       // screened passes of single edits rendered again at the grade's frames, at most
  int pair_confirmations = 2;  // and of pairs, apart: a single's screen that passed and its render that failed does not spend a pair's
  int screen_size = 64;   // the screening canvas's longer side, in pixels
  int wave = 2;           // candidates screened at once, or one a worker: the machine's speed, never the answer
  // A screen's share of the pool's compile and render deadlines (CPU time, as every deadline): a
  // candidate that hangs is dropped after this share, never the grade's failure. The confirming
  // render has the grade's whole deadlines, as the student's own program had.
  double screen_deadline_share = 0.25;
  // A class batch's second pass (repair/classmate_edits.h): the edits the class's passing programs
  // offer that the course's reference does not, at most, from the `classmates` nearest the
  // student's program; tried first, as the first search tried the others.
  int class_candidates = 16;
  int classmates = 3;

  repair::CandidateCounts candidate_counts() const { return {candidates, reference_candidates, class_candidates, classmates, pairs}; }
};

// Whether a report is one the search is for: a failing grade that drew its frames and that
// neither the formula nor the course's catalogue explained. A starter constant the student
// changed (one of `constants`, the grader's own diagnosis) names one change: whether it is the
// only one, and where any other is, only a render says, so the search runs for it too; and for
// the grader's swapped channels, which say what and never where.
bool wants_repair(const grade::Report& report, const std::vector<grade::StarterConstant>& constants);

// Searches the program `failed` drew (a grade job), and writes into `report` what it tried
// (`repair_search`) and, when a repair is confirmed, as much of it as `shown` says among its
// messages (what is wrong; where; the repaired line), an edit at a local `vectors` names said with
// its words ("`toEye`, the direction to the eye, has the wrong sign"). `classmates`, where a class
// batch gives them, offer edits of their own after the reference's. When the
// service cannot run a candidate (the queue full, no worker) the search stops, says so in a
// warning and writes no `repair_search`: the service's trouble is never a different answer.
// `values`, where the failing grade read them (grade/value_reading.h): the edits at the lines where
// a value first departs from the reference's are screened first (repair/search_order.h).
void search_repair(worker::WorkerPool& pool, const worker::Job& failed, const std::string& mesh_bytes, repair::RepairShown shown,
                   const grade::VectorWords& vectors, grade::Report& report, const RepairBudget& budget = {},
                   const std::vector<repair::PassingProgram>& classmates = {}, const repair::ValueAgreement& values = {});

// Whether `classmates` offer any edit of the program `failed` drew (a grade job) that its first
// search, beside the reference alone, did not try: where none, a second search would screen again
// what the first screened, and is not run.
bool class_offers_edits(const worker::Job& failed, const std::vector<repair::PassingProgram>& classmates, const RepairBudget& budget = {});

}  // namespace shadelab::road
