#pragma once
// WebGL's rules on the words and directives of one stage: what the browser's own preprocessor and
// lexer refuse before any parse, where Mesa's go on (docs/webgl-rules.md, "Words and directives"):
//  - a token longer than 1,024 characters, anywhere: a #define's name, a number, a skipped #if
//    group and the ES 1.00 language included;
//  - a word GLSL ES reserves for future use, as a name (after #if and the macros: a macro may
//    carry one in; a word after `.` is a field and never reserved);
//  - a `#line` number that does not fit a 32-bit int;
//  - `invariant a, b;`, a list where the browser's grammar takes one name.
// And one rewrite the driver needs: `#line` with an expression (`#line 10 + 2`, a macro), which
// the browser evaluates and the driver does not read, given to the driver as the number.
#include <string>
#include <string_view>
#include <vector>

#include "shader/glsl_facts.h"

namespace shadelab::shader {

struct LexicalError {
  GlslPoint at;         // in the GLSL the driver gets (column 0 = the line)
  std::string message;  // the browser's words, then where the rule is written
};

std::vector<LexicalError> lexical_errors(std::string_view glsl, GlslVersion version, const GlslFacts& facts);

// Each active `#line` becomes the numbers the preprocessor evaluated it to, on its own line; one
// that evaluates below 0 (which the browser accepts and the driver cannot be told) is left out,
// so the driver numbers the lines after it as they stand.
void evaluate_line_directives(std::string& glsl, const GlslFacts& facts);

}  // namespace shadelab::shader
