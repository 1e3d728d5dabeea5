#pragma once
// The reference's text written in a student's names: the locals the student named otherwise
// (repair/aligned_lines.h), so that an edit that puts back what the reference has (a guard's
// condition, a value) reads as the student's own program.
#include <map>
#include <optional>
#include <string>

#include "repair/stage_tokens.h"

namespace shadelab::repair {

using NameMap = std::map<std::string, std::string, std::less<>>;

// Each reference local the student's stage names otherwise (`norm` for `N`), by the reference's name.
NameMap student_names(const StageTokens& student, const StageTokens& reference);

// The reference's tokens first..last written in the student's names: a local the student names
// otherwise by their name, and, with `expand`, one they do not have by the value the reference
// declares it with (one level: `NdotL` as `dot(N, L)`); uniforms, inputs, calls, numbers and the
// locals both declare as they are. None where a name has no counterpart.
std::optional<std::string> in_student_names(const StageTokens& student, const StageTokens& reference, size_t first, size_t last,
                                            const NameMap& names, bool expand = true);

}  // namespace shadelab::repair
