#pragma once
// A stage's GLSL by line: what the rules read and the rewrites change without moving any line
// (the driver's line numbers map back to the student's file).
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace shadelab::shader {

std::vector<std::string_view> lines_of(std::string_view text);

// Line `number` (1-based) without its newline; empty past the end.
std::string_view line_of(std::string_view text, int number);

// Where `name` stands as a whole word in `line`, or npos.
std::size_t whole_word(std::string_view line, std::string_view name);

bool identifier_start(char c);
bool identifier_char(char c);

// One preprocessing token as a GLSL tokenizer meets it.
struct GlslToken {
  enum class Kind { identifier, number, punctuation } kind;
  std::string_view text;
  int line = 0, column = 0;  // 1-based
};

// Every token of `text` in order, comments skipped (a comment is not a token), directives read
// like the rest. A number is a preprocessing number: digits, letters, `.` and an exponent's sign.
std::vector<GlslToken> tokens_of(std::string_view text);

// Line `number`'s text becomes `with` (one line); its newline stays, so no line moves.
void replace_line(std::string& glsl, int number, std::string_view with);

}  // namespace shadelab::shader
