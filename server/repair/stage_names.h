#pragma once
// The names one stage declares, with their types, and where its main and its conditions are, as
// the repair edits read them
// (repair/repair_edits.h, repair/left_out_edits.h).
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "repair/stage_tokens.h"

namespace shadelab::repair {

using TypedNames = std::map<std::string, std::string, std::less<>>;

// The type each declared name has: `vec3 L`, `uniform vec4 uDiffuseColor`, `in vec3 vNormal`.
TypedNames declared_types(const StageTokens& s);

// A name a stage reads but does not write: a uniform or an input.
TypedNames read_only_names(const StageTokens& s);

// Whether the name at token `i` is read there: not declared, assigned or a field.
bool read_at(const StageTokens& s, size_t i);

// The `{` that opens main's body, or size().
size_t main_start(const StageTokens& s);

// The conditions of a stage's `if`s, in order: the first and last token inside each `if (...)`.
std::vector<std::pair<size_t, size_t>> conditions_of(const StageTokens& s);

}  // namespace shadelab::repair
