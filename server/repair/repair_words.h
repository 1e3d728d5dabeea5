#pragma once
// What a repair's edit says is wrong, in the homework's words and without the repaired text (a
// student may be shown these; the repaired line is for whoever may see the references).
#include <string>
#include <string_view>

#include "repair/repair_edit.h"

namespace shadelab::repair {

// "`L` is not normalised: a direction must be a unit vector". `meaning`: what the edit's subject
// is in the homework's formula, where the course names it (grade/formula_vectors.h): "`L` is not
// normalised: the direction to the light must be a unit vector", "`toEye`, the direction to the
// eye, has the wrong sign".
std::string repair_words(const RepairEdit& edit, std::string_view meaning = {});

// The same mistake in a few words, alike for every student who made it, to count a class by:
// "L not normalised" where `symbol` is the formula's name for the edit's subject ("L"), else the
// subject as written ("`uSpecularColor` in place of another value").
std::string repair_label(const RepairEdit& edit, std::string_view symbol = {});

}  // namespace shadelab::repair
