#include "shader/extension_directives.h"

#include <vector>

#include "shader/glsl_lines.h"

namespace shadelab::shader {

namespace {

// glslang's preprocessor stops at an extension it does not know (and WebGL's list is not its
// list), so for the preprocessing pass each `#extension` becomes a pragma it passes through
// untouched, still subject to #if. Lines keep their numbers.
constexpr std::string_view kExtensionPragma = "#pragma shadelab_extension ";

}  // namespace

std::string extensions_as_pragmas(std::string_view glsl) {
  std::string out;
  size_t start = 0;
  while (start < glsl.size()) {
    size_t end = glsl.find('\n', start);
    end = end == std::string_view::npos ? glsl.size() : end + 1;
    std::string_view line = glsl.substr(start, end - start);
    const size_t hash = line.find_first_not_of(" \t");
    const size_t word = hash == std::string_view::npos || line[hash] != '#' ? std::string_view::npos
                                                                           : line.find_first_not_of(" \t", hash + 1);
    if (word != std::string_view::npos && line.compare(word, 9, "extension") == 0) {
      out += kExtensionPragma;
      out += line.substr(word + 9);
    } else {
      out += line;
    }
    start = end;
  }
  return out;
}

bool is_extension_pragma(std::string_view line) {
  return line.rfind(kExtensionPragma.substr(0, kExtensionPragma.size() - 1), 0) == 0;
}

// `#extension NAME : BEHAVIOR`, token by token, as a WebGL preprocessor reads it: the first token
// out of place decides the shape.
ExtensionDirective read_extension_directive(std::string_view line, int number) {
  const std::vector<GlslToken> tokens = tokens_of(line);
  ExtensionDirective d;
  d.line = number;
  // tokens[0] is '#', tokens[1] is `extension`.
  const auto at = [&](size_t k) -> const GlslToken* { return k < tokens.size() ? &tokens[k] : nullptr; };
  const auto shape = [&](ExtensionDirective::Shape s, const GlslToken* t) {
    d.shape = s;
    d.token = t ? std::string(t->text) : "#extension";
    d.column = t ? t->column : 0;
    return d;
  };
  const GlslToken *name = at(2), *colon = at(3), *behavior = at(4), *extra = at(5);
  if (!name) return shape(ExtensionDirective::Shape::unfinished, nullptr);
  if (name->kind != GlslToken::Kind::identifier) return shape(ExtensionDirective::Shape::name_not_identifier, name);
  d.name = std::string(name->text);
  if (!colon) return shape(ExtensionDirective::Shape::unfinished, nullptr);
  if (colon->text != ":") return shape(ExtensionDirective::Shape::unexpected_token, colon);
  if (!behavior) return shape(ExtensionDirective::Shape::unfinished, nullptr);
  d.behavior = std::string(behavior->text);
  if (d.behavior != "require" && d.behavior != "enable" && d.behavior != "warn" && d.behavior != "disable")
    return shape(ExtensionDirective::Shape::unknown_behavior, name);
  if (extra) return shape(ExtensionDirective::Shape::unexpected_token, extra);
  return d;
}

// The browser's preprocessor refuses `#extension` after a line of code (GLSL ES 3.00 section 3.4;
// Chromium holds GLSL ES 1.00 shaders to it too), counting the source's own words before any
// macro expands: `E` that expands to nothing is code. Only where #if leaves the code in, so the
// preprocessor decides which lines stand: every directive kept (comments out, columns in place),
// every line of code one marker word; a marker it leaves in is a line of code that stands.
namespace {
constexpr std::string_view kCodeMarker = "shadelab_code_line";
}  // namespace

std::string directives_and_code_markers(std::string_view text) {
  std::vector<std::string> lines(lines_of(text).size());
  std::vector<bool> directive(lines.size(), false);
  bool continues = false;  // the last directive line ended in a backslash
  int last_line = 0;
  for (const GlslToken& t : tokens_of(text)) {
    const auto k = static_cast<size_t>(t.line - 1);
    if (t.line != last_line) {
      continues = continues && last_line == t.line - 1;
      directive[k] = t.text == "#" || continues;
      last_line = t.line;
    }
    if (!directive[k]) {
      lines[k] = kCodeMarker;
      continues = false;
      continue;
    }
    lines[k].resize(static_cast<size_t>(t.column - 1), ' ');
    lines[k] += t.text;
    continues = t.text == "\\";
  }
  std::string out;
  for (const auto& line : lines) out += line + "\n";
  return out;
}

int first_code_line(std::string_view preprocessed_skeleton) {
  const auto lines = lines_of(preprocessed_skeleton);
  for (size_t k = 0; k < lines.size(); ++k)
    if (lines[k].find(kCodeMarker) != std::string_view::npos) return static_cast<int>(k) + 1;
  return 0;
}

}  // namespace shadelab::shader
