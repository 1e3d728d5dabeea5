#pragma once
// A confirmed repair, said (docs/grading.md, "Repairs"): "phong_frag.js line 20: `L` is not
// normalised: the direction to the light must be a unit vector." for each of its edits, and, for
// whoever may see the repaired lines, "With `...` the frames match the reference's on every frame
// and light the grade draws." Only a repair a render confirmed is said (road/repair_search.h); the
// engine says each edit (repair/said_repair.h), this puts them in the report.
#include <string_view>
#include <vector>

#include "grade/grade_spec.h"
#include "grade/report.h"
#include "repair/said_repair.h"

namespace shadelab::grade {

// Writes the repair said by `edits` into `report`: its sentences among the messages (a changed
// starter constant of `constants` the grader named in `fragment_text`, the student's fragment
// file, said once, at its line), superseding the formula's "cannot say why", and `found` (and
// `also`, for a pair) in its `repair_search`, which the search has set.
void state_repair(std::vector<repair::SaidEdit> edits, const std::vector<StarterConstant>& constants, const std::string& fragment_text,
                  Report& report);

}  // namespace shadelab::grade
