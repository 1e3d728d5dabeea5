#pragma once
// The value of an `#if` / `#elif` condition written in literals only (`0 && 1/0`), read as the
// browser's preprocessor reads it: C's operators and precedence, `&&` and `||` skipping their
// right side where the left decides. glslang divides on that side too and refuses `#if 0 && 1/0`,
// which the browser takes, so such a line reaches glslang and the driver as the value it has.
#include <optional>
#include <string_view>

namespace shadelab::shader {

// The condition's value, or nothing where it names anything (a macro, `defined`), is not a
// well-formed expression, or divides by zero where it is evaluated: those stay the compiler's to
// judge.
std::optional<long long> literal_condition_value(std::string_view condition);

}  // namespace shadelab::shader
