#pragma once
// `#extension` as WebGL's preprocessor reads it, in the source's own words: each directive's shape
// (`#extension NAME : BEHAVIOR`), and whether a line of code stands before it. glslang's
// preprocessor decides which lines #if leaves in (shader/glsl_facts.cpp runs it); these prepare
// its input and read its output, each line in its place.
#include <string>
#include <string_view>

#include "shader/glsl_facts.h"

namespace shadelab::shader {

// One `#extension` line of the student's source (comments allowed), as the browser reads it.
ExtensionDirective read_extension_directive(std::string_view line, int number);

// Every `#extension` line as a pragma glslang passes through untouched (its preprocessor stops at
// an extension it does not know, and WebGL's list is not its list), still subject to #if.
std::string extensions_as_pragmas(std::string_view glsl);

// Whether a line of glslang's output is such a pragma: an `#extension` #if left in.
bool is_extension_pragma(std::string_view preprocessed_line);

// The stage's skeleton: every directive kept (comments out, columns in place), every line of code
// one marker word, so a preprocess of it says which lines of code #if leaves in.
std::string directives_and_code_markers(std::string_view text);

// The first line of a preprocessed skeleton where a line of code stands (1-based; 0: none).
int first_code_line(std::string_view preprocessed_skeleton);

}  // namespace shadelab::shader
