#pragma once
// A confirmed repair, said (docs/grading.md, "Repairs"): "phong_frag.js line 20: `L` is not
// normalised: the direction to the light must be a unit vector." for each of its edits, and, for
// whoever may see the repaired lines, "With `...` the frames match the reference's on every frame
// and light the grade draws." Only a repair a render confirmed is said (road/repair_search.h).
#include <vector>

#include "grade/formula_vectors.h"
#include "grade/grade_spec.h"
#include "repair/repair_candidates.h"
#include "grade/report.h"

namespace shadelab::grade {

// Writes the repair of `p` by `edits` into `report`: its sentences among the messages (as far as
// `shown` allows; a local `vectors` names said in its words; a changed starter constant of
// `constants` the grader named said once, at its line), superseding the formula's "cannot say
// why", and `found` (and `also`, for a pair) in its `repair_search`, which the search has set.
void state_repair(const repair::RepairProgram& p, const std::vector<repair::RepairEdit>& edits, repair::RepairShown shown, const VectorWords& vectors,
                  const std::vector<StarterConstant>& constants, Report& report);

}  // namespace shadelab::grade
