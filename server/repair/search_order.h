#pragma once
// The repair search's order (docs/grading.md, "Where a value first departs"): which candidates are
// screened in what phase, decided by the repair engine from the program's reading, its values and
// what the screens so far found. Drawing a candidate is the caller's (road/repair_search.cpp runs
// each on the service's workers): this file asks for screens through `Screens` and never renders.
//
// The phases, each only while nothing is confirmed:
// 1. the singles that align their line with the reference or edit a line where a value departs,
//    those whose edit makes the change the values say that line needs (repair/value_change.h)
//    first, and where these are at two lines, their pairs, then phase 3 for them alone (the
//    nearest of them however far it draws, paired with the edits making the changes its values
//    still need, or putting back a value no one change makes), before the other singles;
// 2. where two lines depart, the pairs of those singles at the two lines;
// 3. the single of phase 1 that drew nearest the reference, paired with each single at a line
//    where its own program's values still depart (a second mistake the first one's error hid);
// 4. the other singles;
// 5. every pair repair::pair_candidates makes, less those tried, `pairs` in all.
#include <optional>
#include <vector>

#include "repair/repair_candidates.h"
#include "repair/value_probes.h"

namespace shadelab::repair {

// How one phase's screens came out.
enum class Pass { confirmed, budget_spent, none_passed, trouble };

// What the search asks of whoever draws its candidates.
class Screens {
 public:
  virtual ~Screens() = default;
  // Screens `candidates` in order and renders each screened pass again at the grade's frames, within
  // what is `left` of a budget of confirmations (spending it), until one is confirmed (`winner`).
  // `distances`, where given, gets each screen's distance from the reference (0 to 1).
  virtual Pass try_within(const std::vector<RepairCandidate>& candidates, int& left, std::vector<double>* distances,
                          const RepairCandidate** winner) = 0;
  // The student's own program's distance on the screening canvas; none where it could not be drawn.
  virtual std::optional<double> own_distance() = 0;
  // The values `c`'s program computes beside the reference's (grade/value_reading.h); none where
  // they could not be read.
  virtual std::optional<ValueAgreement> values_of(const RepairCandidate& c) = 0;
};

// Confirmations a search may spend: on singles, and on pairs apart (a single's screen that passed
// and whose render failed does not spend a pair's).
struct Confirmations {
  int singles = 2, pairs = 2;
};

struct SearchOutcome {
  Pass pass = Pass::none_passed;
  std::vector<RepairEdit> edits;  // the confirmed candidate's
};

// The search of `p`'s repair in the phases above, `values` read where the student's grade failed.
SearchOutcome search_in_order(const RepairProgram& p, const CandidateCounts& counts, Confirmations confirmations,
                              const ValueAgreement& values, Screens& screens);

}  // namespace shadelab::repair
