#pragma once
// The names one stage declares, with their types, and where its main, its statements, its helper
// functions and its conditions are, as the repair edits read them (repair/repair_edits.h,
// repair/left_out_edits.h).
#include <map>
#include <string>
#include <string_view>
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

// Whether token `i` begins a statement: the token before it is `;`, `{` or `}`.
bool statement_start(const StageTokens& s, size_t i);

// The `;` that ends the statement token `i` is in, or size().
size_t statement_end(const StageTokens& s, size_t i);

// Whether a token from `first` to `last` (both kept) is `text`.
bool has_token(const StageTokens& s, std::string_view text, size_t first, size_t last);

// How many times the stage calls `name`.
size_t calls_of(const StageTokens& s, std::string_view name);

// Whether the stage reads `name` anywhere.
bool reads(const StageTokens& s, std::string_view name);

// Whether token `i` is inside main's body.
bool main_of(const StageTokens& s, size_t i);

// A helper function of the stage's (not main): its return type, the first and last token of its
// parameters' list, and its body's `{` and `}`.
struct Helper {
  std::string_view type;
  size_t params_first = 0, params_last = 0, open = 0, close = 0;
};

std::vector<Helper> helpers_of(const StageTokens& s);

}  // namespace shadelab::repair
