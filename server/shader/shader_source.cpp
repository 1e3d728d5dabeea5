#include "shader/shader_source.h"

#include <algorithm>
#include <cctype>
#include <optional>

namespace shadelab::shader {

std::string_view to_string(Stage stage) { return stage == Stage::vertex ? "vertex" : "fragment"; }

namespace {

// A cursor over the file that knows its line and column.
struct Cursor {
  const std::string& text;
  size_t pos = 0;
  int line = 1, column = 1;

  bool done() const { return pos >= text.size(); }
  char peek(size_t ahead = 0) const { return pos + ahead < text.size() ? text[pos + ahead] : '\0'; }
  char next() {
    const char c = text[pos++];
    if (c == '\n') {
      ++line;
      column = 1;
    } else if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) {
      ++column;  // continuation bytes of a UTF-8 sequence do not start a column
    }
    return c;
  }
  bool starts_with(std::string_view s) const { return text.compare(pos, s.size(), s) == 0; }
};

Error source_error(ErrorCode code, const ShaderFile& file, Stage stage, int line, int column, std::string message) {
  Error e = make_error(code, message);
  e.diagnostics.push_back(Diagnostic{std::string(to_string(stage)), file.name, line, column, "error", std::move(message)});
  return e;
}

// Returns the byte offset of the first invalid UTF-8 sequence, or npos.
size_t invalid_utf8_at(const std::string& s) {
  size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    int extra = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xE ? 2 : (c >> 3) == 0x1E ? 3 : -1;
    if (extra < 0 || (extra == 1 && c < 0xC2) || i + static_cast<size_t>(extra) >= s.size())
      return i;
    for (int k = 1; k <= extra; ++k)
      if ((static_cast<unsigned char>(s[i + static_cast<size_t>(k)]) & 0xC0) != 0x80) return i;
    i += static_cast<size_t>(extra) + 1;
  }
  return std::string::npos;
}

std::pair<int, int> line_column_at(const std::string& s, size_t offset) {
  Cursor c{s};
  while (c.pos < offset && !c.done()) c.next();
  return {c.line, c.column};
}

// The bytes of the ECMAScript WhiteSpace or LineTerminator that starts at the cursor (0 for none):
// ASCII's, U+00A0, U+FEFF, U+1680, U+2000-U+200A, U+2028, U+2029, U+202F, U+205F and U+3000.
// A `//` comment ends at U+2028 and U+2029 as at LF: read otherwise, `// note` U+2028 `code` hides
// code from this reader that a browser runs.
size_t js_space_at(const Cursor& c) {
  const auto b = [&](size_t k) { return static_cast<unsigned char>(c.peek(k)); };
  if (b(0) < 0x80) return std::isspace(b(0)) ? 1 : 0;
  if (b(0) == 0xC2 && b(1) == 0xA0) return 2;
  if (b(0) == 0xEF && b(1) == 0xBB && b(2) == 0xBF) return 3;
  if (b(0) == 0xE1 && b(1) == 0x9A && b(2) == 0x80) return 3;
  if (b(0) == 0xE2 && b(1) == 0x80 && ((b(2) >= 0x80 && b(2) <= 0x8A) || b(2) == 0xA8 || b(2) == 0xA9 || b(2) == 0xAF)) return 3;
  if (b(0) == 0xE2 && b(1) == 0x81 && b(2) == 0x9F) return 3;
  if (b(0) == 0xE3 && b(1) == 0x80 && b(2) == 0x80) return 3;
  return 0;
}

// LF (CR is LF by now), U+2028 or U+2029.
bool js_line_terminator_at(const Cursor& c) {
  return c.peek() == '\n' || c.starts_with("\xE2\x80\xA8") || c.starts_with("\xE2\x80\xA9");
}

void skip(Cursor& c, size_t bytes) {
  for (size_t i = 0; i < bytes; ++i) c.next();
}

// Skips ECMAScript white space, line terminators and comments.
void skip_js_space(Cursor& c) {
  while (!c.done()) {
    if (const size_t space = js_space_at(c)) {
      skip(c, space);
    } else if (c.starts_with("//")) {
      while (!c.done() && !js_line_terminator_at(c)) c.next();
    } else if (c.starts_with("/*")) {
      c.next(), c.next();
      while (!c.done() && !c.starts_with("*/")) c.next();
      if (!c.done()) c.next(), c.next();
    } else {
      return;
    }
  }
}

// Whether the byte after a keyword continues an identifier (`exports`, `export_`, `export$`, or a
// letter beyond ASCII), so the keyword is not one.
bool continues_identifier(const Cursor& c, size_t ahead) {
  const auto b = static_cast<unsigned char>(c.peek(ahead));
  if (b == 0) return false;
  if (b >= 0x80) {
    Cursor after = c;
    skip(after, ahead);
    return js_space_at(after) == 0;
  }
  return std::isalnum(b) || b == '_' || b == '$' || b == '\\';
}

bool looks_like_module(const std::string& text) {
  Cursor c{text};
  skip_js_space(c);
  return c.starts_with("export") && !continues_identifier(c, 6);
}

// Appends one unwrapped character, opening a new GLSL line in the map after each newline.
// A new run starts wherever the file and the GLSL stop advancing together: a line's start, an
// escape sequence, a line continuation.
struct Emitter {
  UnwrappedSource& out;
  bool at_line_start = true;
  int glsl_line = 1, glsl_column = 1;
  LineOrigin next_in_file{0, 0};  // where the next character continues the current run

  void put(char ch, int file_line, int file_column) {
    out.glsl.push_back(ch);
    if ((static_cast<unsigned char>(ch) & 0xC0) == 0x80) return;  // within the character just put
    if (at_line_start) {
      out.lines.push_back({file_line, file_column});
      at_line_start = false;
    }
    if (out.runs.empty() || file_line != next_in_file.file_line || file_column != next_in_file.file_column ||
        glsl_column == 1)
      out.runs.push_back({glsl_line, glsl_column, {file_line, file_column}});
    next_in_file = {file_line, file_column + 1};
    if (ch == '\n') {
      ++glsl_line, glsl_column = 1;
      at_line_start = true;
    } else {
      ++glsl_column;
    }
  }
  void finish(int file_line, int file_column) {
    if (at_line_start) {
      out.lines.push_back({file_line, file_column});
      out.runs.push_back({glsl_line, 1, {file_line, file_column}});
    }
  }
};

// Characters (not UTF-8 continuation bytes) on 1-based `line` of `text`.
int glsl_line_length(const std::string& text, int line) {
  size_t begin = 0;
  for (int l = 1; l < line && begin != std::string::npos; ++l) {
    begin = text.find('\n', begin);
    if (begin != std::string::npos) ++begin;
  }
  if (begin == std::string::npos) return 0;
  const size_t end = std::min(text.find('\n', begin), text.size());
  int characters = 0;
  for (size_t i = begin; i < end; ++i) characters += (static_cast<unsigned char>(text[i]) & 0xC0) != 0x80;
  return characters;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

void append_utf8(std::string& s, unsigned cp) {
  if (cp >= 0xD800 && cp <= 0xDFFF) cp = 0xFFFD;  // a lone surrogate, as a browser encodes it
  if (cp >= 0x10000) {
    s.push_back(static_cast<char>(0xF0 | (cp >> 18)));
    s.push_back(static_cast<char>(0x80 | ((cp >> 12) & 0x3F)));
    s.push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    s.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else if (cp < 0x80) {
    s.push_back(static_cast<char>(cp));
  } else if (cp < 0x800) {
    s.push_back(static_cast<char>(0xC0 | (cp >> 6)));
    s.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else {
    s.push_back(static_cast<char>(0xE0 | (cp >> 12)));
    s.push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    s.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  }
}

// What one escape sequence stands for, read as ECMAScript reads it in a module (strict code) and
// a template: its UTF-8 bytes (none for a line continuation), or why a browser refuses it.
struct Escaped {
  std::string bytes;
  std::string refusal;
};

// `count` hex digits exactly; nullopt when fewer are there.
std::optional<unsigned> hex_digits(Cursor& c, int count) {
  unsigned value = 0;
  for (int k = 0; k < count; ++k) {
    if (hex_value(c.peek(static_cast<size_t>(k))) < 0) return std::nullopt;
    value = value * 16 + static_cast<unsigned>(hex_value(c.peek(static_cast<size_t>(k))));
  }
  skip(c, static_cast<size_t>(count));
  return value;
}

// \uXXXX or \u{X...}, the `u` read; a high surrogate followed by \u and a low one is one code point.
std::optional<unsigned> unicode_escape(Cursor& c) {
  if (c.peek() == '{') {
    size_t digits = 0;
    while (hex_value(c.peek(1 + digits)) >= 0) ++digits;
    if (digits == 0 || c.peek(1 + digits) != '}') return std::nullopt;
    unsigned value = 0;
    for (size_t k = 0; k < digits && value <= 0x10FFFF; ++k) value = value * 16 + static_cast<unsigned>(hex_value(c.peek(1 + k)));
    if (value > 0x10FFFF) return std::nullopt;
    skip(c, digits + 2);
    return value;
  }
  const auto unit = hex_digits(c, 4);
  if (!unit || *unit < 0xD800 || *unit > 0xDBFF || !c.starts_with("\\u")) return unit;
  Cursor low = c;
  skip(low, 2);
  const auto second = hex_digits(low, 4);
  if (!second || *second < 0xDC00 || *second > 0xDFFF) return unit;
  skip(c, 6);
  return 0x10000 + ((*unit - 0xD800) << 10) + (*second - 0xDC00);
}

// The escape whose backslash was just read.
Escaped read_escape(Cursor& c) {
  if (c.done()) return {};  // reported as unclosed on the next turn
  if (js_line_terminator_at(c)) {
    skip(c, c.peek() == '\n' ? 1 : 3);  // a line continuation: JS drops both
    return {};
  }
  const char esc = c.next();
  const auto code_point = [](unsigned cp) {
    std::string bytes;
    append_utf8(bytes, cp);
    return Escaped{bytes, {}};
  };
  switch (esc) {
    case 'n': return {"\n", {}};
    case 't': return {"\t", {}};
    case 'r': return {"\r", {}};
    case 'b': return {"\b", {}};
    case 'f': return {"\f", {}};
    case 'v': return {"\v", {}};
    case 'x': {
      const auto value = hex_digits(c, 2);
      return value ? code_point(*value) : Escaped{{}, "`\\x` must be followed by two hex digits"};
    }
    case 'u': {
      const auto value = unicode_escape(c);
      return value ? code_point(*value) : Escaped{{}, "`\\u` must be followed by four hex digits or {a code point of at most 10FFFF}"};
    }
    default: break;
  }
  if (esc == '0' && !std::isdigit(static_cast<unsigned char>(c.peek()))) return {std::string(1, '\0'), {}};  // rejected later, like any NUL
  if (std::isdigit(static_cast<unsigned char>(esc)))
    return {{}, std::string("`\\") + esc + "` is an octal escape, which a module's strings and templates refuse"};
  return {std::string(1, esc), {}};  // \\ \` \' \" \$ and JS's identity escapes (a UTF-8 character's first byte)
}

Expected<UnwrappedSource> unwrap_module(const ShaderFile& file, const std::string& text, Stage stage) {
  Cursor c{text};
  skip_js_space(c);
  skip(c, 6);  // "export"
  skip_js_space(c);
  if (!c.starts_with("default") || continues_identifier(c, 7))
    return source_error(ErrorCode::shader_source_invalid, file, stage, c.line, c.column,
                        "expected `export default` followed by the shader string");
  skip(c, 7);
  skip_js_space(c);
  const char quote = c.peek();
  if (quote != '`' && quote != '\'' && quote != '"')
    return source_error(ErrorCode::shader_source_invalid, file, stage, c.line, c.column,
                        "expected a string after `export default` (a back-tick `...` template or a quoted string)");
  const int open_line = c.line, open_column = c.column;
  c.next();

  UnwrappedSource out;
  out.from_js_module = true;
  Emitter emit{out};
  // A CR the string holds (an escape: raw ones are LF by now) is a line end, as the page reads it
  // (CR LF and a lone CR become LF): written when the next character is known.
  bool pending_cr = false;
  const auto put = [&](const std::string& bytes, int line, int column) {
    for (char b : bytes) {
      if (b == '\r') {
        if (pending_cr) emit.put('\n', line, column);
        pending_cr = true;
        continue;
      }
      if (pending_cr && b != '\n') emit.put('\n', line, column);
      pending_cr = false;
      emit.put(b, line, column);
    }
  };
  while (true) {
    if (c.done())
      return source_error(ErrorCode::shader_source_invalid, file, stage, open_line, open_column,
                          std::string("the shader string opened here is never closed (missing ") + quote + ")");
    const int line = c.line, column = c.column;
    if (c.peek() == quote) {
      c.next();
      break;
    }
    if (quote != '`' && c.peek() == '\n')
      return source_error(ErrorCode::shader_source_invalid, file, stage, line, column,
                          "a quoted JS string cannot span lines; browsers reject this module (use back-ticks)");
    if (quote == '`' && c.starts_with("${"))
      return source_error(ErrorCode::shader_source_invalid, file, stage, line, column,
                          "template interpolation ${...} cannot be evaluated here; write the value into the shader");
    if (c.peek() != '\\') {
      put(std::string(1, c.next()), line, column);
      continue;
    }
    c.next();
    const Escaped escaped = read_escape(c);
    if (!escaped.refusal.empty()) return source_error(ErrorCode::shader_source_invalid, file, stage, line, column, escaped.refusal);
    put(escaped.bytes, line, column);
  }
  if (pending_cr) emit.put('\n', c.line, c.column);
  emit.finish(c.line, c.column);
  for (skip_js_space(c); c.peek() == ';'; skip_js_space(c)) c.next();  // empty statements
  if (!c.done())
    return source_error(ErrorCode::shader_source_invalid, file, stage, c.line, c.column,
                        "unexpected text after the shader string; the module should hold only `export default`");
  return out;
}

UnwrappedSource identity(const std::string& text) {
  UnwrappedSource out;
  out.glsl = text;
  const auto lines = std::count(text.begin(), text.end(), '\n') + 1;
  for (int i = 1; i <= lines; ++i) {
    out.lines.push_back({i, 1});
    out.runs.push_back({i, 1, {i, 1}});
  }
  return out;
}

// WebGL 2 compiles GLSL ES 3.00 (`#version 300 es`, which must be on the first line) and GLSL ES
// 1.00 (`#version 100`, or no #version directive at all).
Expected<GlslVersion> check_version(const ShaderFile& file, const UnwrappedSource& src, Stage stage) {
  const std::string first_line = src.glsl.substr(0, src.glsl.find('\n'));
  size_t i = first_line.find_first_not_of(" \t");
  if (i != std::string::npos && first_line.compare(i, 8, "#version") == 0) {
    std::string rest = first_line.substr(i + 8);
    rest.erase(0, rest.find_first_not_of(" \t"));
    rest.erase(rest.find_last_not_of(" \t\r") + 1);
    if (rest.rfind("300", 0) == 0 && rest.find("es") != std::string::npos) return GlslVersion::es300;
    if (rest == "100" || rest.rfind("100 ", 0) == 0 || rest.rfind("100\t", 0) == 0) return GlslVersion::es100;
    const auto at = src.locate(1, static_cast<int>(i) + 1);
    return source_error(ErrorCode::missing_version, file, stage, at.file_line, at.file_column,
                        "WebGL2 compiles `#version 300 es` (GLSL ES 3.00) or `#version 100` (GLSL ES 1.00); found `" +
                            first_line.substr(i) + "`");
  }
  const size_t later = src.glsl.find("#version");
  if (later == std::string::npos) return GlslVersion::es100;  // no directive: GLSL ES 1.00
  const int glsl_line = static_cast<int>(std::count(src.glsl.begin(), src.glsl.begin() + static_cast<long>(later), '\n')) + 1;
  const auto at = src.locate(glsl_line, 1);
  return source_error(ErrorCode::missing_version, file, stage, at.file_line, at.file_column,
                      "`#version` must be on the shader's very first line (WebGL2 rejects anything before "
                      "it, even a blank line after the opening back-tick)");
}

}  // namespace

Status check_same_version(const UnwrappedSource& vertex, const UnwrappedSource& fragment, const ShaderFile& fragment_file) {
  if (vertex.version == fragment.version) return Ok{};
  const auto at = fragment.locate(1, 1);
  std::string message = "the vertex shader is " + std::string(to_string(vertex.version)) + " and the fragment shader " +
                        std::string(to_string(fragment.version)) +
                        ": a program links shaders of one version (both `#version 300 es`, or both GLSL ES 1.00)";
  Error e = make_error(ErrorCode::link_failed, message);
  e.diagnostics.push_back(Diagnostic{"link", fragment_file.name, at.file_line, at.file_column, "error", std::move(message)});
  return e;
}

std::string_view to_string(GlslVersion version) { return version == GlslVersion::es100 ? "GLSL ES 1.00" : "GLSL ES 3.00"; }

LineOrigin UnwrappedSource::locate(int glsl_line, int glsl_column) const {
  if (lines.empty() || glsl_line < 1) return {0, 0};
  const int line = std::min<int>(glsl_line, static_cast<int>(lines.size()));
  const auto& origin = lines[static_cast<size_t>(line - 1)];
  // A column past the end of its line (a driver's, or a line clamped above) is no place in the
  // file: the line alone is located.
  if (glsl_column < 1 || line != glsl_line || glsl_column > glsl_line_length(glsl, line) + 1) return {origin.file_line, 0};
  // The last run that starts at or before (line, column): within it, one GLSL character is one
  // file character.
  const auto after = std::upper_bound(runs.begin(), runs.end(), std::pair{line, glsl_column}, [](const std::pair<int, int>& at, const MappedRun& r) {
    return at < std::pair{r.glsl_line, r.glsl_column};
  });
  if (after == runs.begin() || std::prev(after)->glsl_line != line) return {origin.file_line, origin.file_column};
  const MappedRun& run = *std::prev(after);
  return {run.origin.file_line, run.origin.file_column + (glsl_column - run.glsl_column)};
}

Expected<UnwrappedSource> unwrap(const ShaderFile& file, Stage stage, const SourceLimits& limits) {
  if (file.text.size() > limits.max_bytes)
    return source_error(ErrorCode::shader_source_invalid, file, stage, 0, 0,
                        "the " + std::string(to_string(stage)) + " shader is " + std::to_string(file.text.size()) +
                            " bytes; the limit is " + std::to_string(limits.max_bytes));
  std::string text = file.text;
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
  // CRLF and lone CR become LF; columns are unaffected because the CR ends its line.
  std::string normalized;
  normalized.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\r') {
      normalized.push_back('\n');
      if (i + 1 < text.size() && text[i + 1] == '\n') ++i;
    } else {
      normalized.push_back(text[i]);
    }
  }
  if (const size_t bad = invalid_utf8_at(normalized); bad != std::string::npos) {
    const auto [line, column] = line_column_at(normalized, bad);
    return source_error(ErrorCode::shader_source_invalid, file, stage, line, column,
                        "the shader is not valid UTF-8 at this point");
  }
  if (std::string::npos == normalized.find_first_not_of(" \t\n"))
    return source_error(ErrorCode::shader_source_invalid, file, stage, 0, 0,
                        "the " + std::string(to_string(stage)) + " shader is empty");

  Expected<UnwrappedSource> unwrapped = looks_like_module(normalized) ? unwrap_module(file, normalized, stage)
                                                                      : Expected<UnwrappedSource>(identity(normalized));
  if (!unwrapped) return unwrapped;
  if (const size_t nul = unwrapped->glsl.find('\0'); nul != std::string::npos) {
    const int glsl_line = static_cast<int>(std::count(unwrapped->glsl.begin(), unwrapped->glsl.begin() + static_cast<long>(nul), '\n')) + 1;
    const auto at = unwrapped->locate(glsl_line, 0);
    return source_error(ErrorCode::shader_source_invalid, file, stage, at.file_line, 0,
                        "the shader contains a NUL byte");
  }
  auto version = check_version(file, *unwrapped, stage);
  if (!version) return version.take_error();
  unwrapped->version = *version;
  return unwrapped;
}

}  // namespace shadelab::shader
