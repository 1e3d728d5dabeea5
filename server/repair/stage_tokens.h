#pragma once
// One stage's GLSL as the repair edits read it (repair/repair_edits.h, repair/reference_edits.h): its
// tokens, the bytes each covers, and how far a call, an operand or an expression reaches. A
// search reads each stage of each program into tokens once, for every edit it looks for.
#include <algorithm>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "repair/repair_edit.h"
#include "shader/glsl_lines.h"

namespace shadelab::repair {

using shader::GlslToken;

inline bool one_of(std::string_view s, std::initializer_list<std::string_view> words) {
  return std::find(words.begin(), words.end(), s) != words.end();
}

// Tokens that may stand before a unary operator or an operand's start: never an operand's end.
// Punctuation is one character a token (shader/glsl_lines.h): `+=` is `+` then `=`.
inline bool before_operand(std::string_view s) {
  return one_of(s, {"(", ",", "=", "+", "-", "*", "/", "?", ":", "return", "{", ";", "<", ">", "!"});
}

// One stage's tokens, with the spans they cover in its GLSL (a view: the text outlives them).
struct StageTokens {
  std::string_view glsl;
  std::vector<GlslToken> t;
  shader::Stage stage;

  StageTokens(std::string_view text, shader::Stage s) : glsl(text), t(shader::tokens_of(text)), stage(s) {}

  size_t size() const { return t.size(); }
  bool is(size_t i, std::string_view s) const { return i < t.size() && t[i].text == s; }
  bool identifier(size_t i) const { return i < t.size() && t[i].kind == GlslToken::Kind::identifier; }
  bool number(size_t i) const { return i < t.size() && t[i].kind == GlslToken::Kind::number; }
  size_t begin(size_t i) const { return static_cast<size_t>(t[i].text.data() - glsl.data()); }
  size_t end(size_t i) const { return begin(i) + t[i].text.size(); }
  // Tokens first..last, inclusive, as written (their spaces and comments included).
  std::string_view text(size_t first, size_t last) const { return glsl.substr(begin(first), end(last) - begin(first)); }

  // The `)` that closes the `(` at `open`; size() when none does.
  size_t close_of(size_t open) const {
    int depth = 0;
    for (size_t i = open; i < t.size(); ++i) {
      if (is(i, "(") || is(i, "[")) ++depth;
      if ((is(i, ")") || is(i, "]")) && --depth == 0) return i;
    }
    return t.size();
  }
  // The last token of the expression that starts at `first`: before the `;`, `,` or closing
  // bracket at its own depth.
  size_t expression_last(size_t first) const {
    int depth = 0;
    for (size_t i = first; i < t.size(); ++i) {
      if (is(i, "(") || is(i, "[")) ++depth;
      if (is(i, ")") || is(i, "]") || is(i, "}")) {
        if (depth == 0) return i - 1;
        --depth;
      }
      if (depth == 0 && (is(i, ";") || is(i, ","))) return i - 1;
    }
    return t.size() - 1;
  }
  // The last token of the operand that starts at `first`: a name or a number, a call, a
  // parenthesis, each with its fields (`.xyz`) and indices after it.
  size_t operand_last(size_t first) const {
    size_t i = first;
    if (is(i, "(")) i = close_of(i);
    else if (identifier(i) && is(i + 1, "(")) i = close_of(i + 1);
    while (i + 2 < t.size() && (is(i + 1, ".") || is(i + 1, "["))) i = is(i + 1, ".") ? i + 2 : close_of(i + 1);
    return std::min(i, t.size() - 1);
  }
  // The arguments of the call whose `(` is at `open`: each as its first and last token.
  std::vector<std::pair<size_t, size_t>> arguments(size_t open) const {
    std::vector<std::pair<size_t, size_t>> out;
    const size_t close = close_of(open);
    for (size_t i = open + 1; i < close;) {
      const size_t last = expression_last(i);
      out.emplace_back(i, last);
      i = last + 2;
    }
    return out;
  }
  // The name of the call an argument at `i` is inside, or "".
  std::string_view enclosing_call(size_t i) const {
    int depth = 0;
    for (size_t k = i; k-- > 0;) {
      if (is(k, ")")) ++depth;
      if (is(k, "(") && depth-- == 0) return k > 0 && identifier(k - 1) ? t[k - 1].text : std::string_view();
    }
    return {};
  }

  RepairEdit edit(RepairKind kind, size_t first_byte, size_t end_byte, std::string with, size_t at, std::string_view subject) const {
    RepairEdit e;
    e.stage = stage;
    e.kind = kind;
    e.begin = first_byte;
    e.end = end_byte;
    e.with = std::move(with);
    e.line = t[at].line;
    e.subject = std::string(subject);
    return e;
  }
  RepairEdit replace(RepairKind kind, size_t first, size_t last, std::string with, std::string_view subject) const {
    return edit(kind, begin(first), end(last), std::move(with), first, subject);
  }
};

// A program's two stages, each read into tokens; empty stages for a program there is none of
// (a grade with no reference).
struct ProgramTokens {
  StageTokens vertex, fragment;

  ProgramTokens() : ProgramTokens(std::string_view(), std::string_view()) {}
  ProgramTokens(std::string_view vertex_glsl, std::string_view fragment_glsl)
      : vertex(vertex_glsl, shader::Stage::vertex), fragment(fragment_glsl, shader::Stage::fragment) {}
  explicit ProgramTokens(const StagePair& p) : ProgramTokens(p.vertex, p.fragment) {}
  const StageTokens& operator[](shader::Stage s) const { return s == shader::Stage::vertex ? vertex : fragment; }
};

// `text` without its spaces, tabs and newlines: two lines that differ only there read the same.
inline std::string unspaced(std::string_view text) {
  std::string kept;
  for (const char c : text)
    if (c != ' ' && c != '\t' && c != '\n' && c != '\r') kept += c;
  return kept;
}

}  // namespace shadelab::repair
