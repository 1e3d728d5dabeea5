#pragma once
// A light scan of GLSL for rewrites that must keep every line where it is (the driver's line
// numbers map back to the student's file): comments and preprocessor lines skipped, braces and
// parentheses counted, each global statement's words and declared names collected. Not a parser
// (glsl_facts.h runs glslang for that): a rewrite built on this scan is compiled by the driver,
// which rejects what the scan misread.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace shadelab::shader {

struct GlslWord {
  std::string text;
  std::size_t offset = 0;  // into the scanned GLSL
};

// One statement at global scope, up to its ';'. A brace ends a statement unfinished (a function's
// body, a struct's members): what follows a struct's '}' is a statement of its own.
struct GlobalStatement {
  std::vector<GlslWord> words;     // identifiers outside parentheses (a layout's are inside)
  std::vector<std::string> names;  // the name of each declarator (split at top-level commas)
  bool has_parameters = false;     // a '(' not after `layout`: a function, not a declaration
  bool has_brackets = false;       // a '[' outside parentheses: an array (of a declarator or its type)
  std::size_t layout_begin = 0, layout_end = 0;  // `layout(...)`, end past its ')'; equal when none
  std::size_t semicolon = 0;

  bool has(std::string_view word) const;
};

struct GlslScan {
  std::vector<GlobalStatement> statements;
  std::vector<GlslWord> identifiers;  // every identifier and keyword outside comments and directives
  bool defines_macro = false;         // a `#define` line: code appended after it may not mean what it says
};

GlslScan scan_glsl(std::string_view glsl);

}  // namespace shadelab::shader
