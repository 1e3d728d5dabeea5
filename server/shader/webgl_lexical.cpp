#include "shader/webgl_lexical.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cstdlib>

#include "shader/glsl_lines.h"

namespace shadelab::shader {

namespace {

// The browser's longest token: a name's or a number's.
constexpr size_t kMaxTokenLength = 1024;

// GLSL ES 3.00 section 3.8, "reserved for future use". (sampler2DRect and sampler3DRect are
// there too; the browser reads them as types it does not have, refused all the same.)
constexpr auto kReservedEs300 = std::to_array<std::string_view>({
    "attribute", "varying", "coherent", "volatile", "restrict", "readonly", "writeonly", "resource", "atomic_uint",
    "noperspective", "patch", "sample", "subroutine", "common", "partition", "active", "asm", "class", "union", "enum",
    "typedef", "template", "this", "goto", "inline", "noinline", "public", "static", "extern", "external", "interface",
    "long", "short", "double", "half", "fixed", "unsigned", "superp", "input", "output", "hvec2", "hvec3", "hvec4",
    "dvec2", "dvec3", "dvec4", "fvec2", "fvec3", "fvec4", "sampler3DRect", "filter", "image1D", "image2D", "image3D",
    "imageCube", "iimage1D", "iimage2D", "iimage3D", "iimageCube", "uimage1D", "uimage2D", "uimage3D", "uimageCube",
    "image1DArray", "image2DArray", "iimage1DArray", "iimage2DArray", "uimage1DArray", "uimage2DArray", "image1DShadow",
    "image2DShadow", "image1DArrayShadow", "image2DArrayShadow", "imageBuffer", "iimageBuffer", "uimageBuffer",
    "sampler1D", "sampler1DShadow", "sampler1DArray", "sampler1DArrayShadow", "isampler1D", "isampler1DArray",
    "usampler1D", "usampler1DArray", "sampler2DRect", "sampler2DRectShadow", "isampler2DRect", "usampler2DRect",
    "samplerBuffer", "isamplerBuffer", "usamplerBuffer", "sampler2DMS", "isampler2DMS", "usampler2DMS",
    "sampler2DMSArray", "isampler2DMSArray", "usampler2DMSArray", "sizeof", "cast", "namespace", "using"});

// GLSL ES 1.00 section 3.7, then the four the browser reserves in ES 1.00 too (probed in Chromium:
// it refuses them as names in both languages; docs/webgl-rules.md).
constexpr auto kReservedEs100 = std::to_array<std::string_view>({
    "asm", "class", "union", "enum", "typedef", "template", "this", "packed", "goto", "switch", "default", "inline",
    "noinline", "volatile", "public", "static", "extern", "external", "interface", "flat", "long", "short", "double",
    "half", "fixed", "unsigned", "superp", "input", "output", "hvec2", "hvec3", "hvec4", "dvec2", "dvec3", "dvec4",
    "fvec2", "fvec3", "fvec4", "sampler1D", "sampler3D", "sampler1DShadow", "sampler2DShadow", "sampler2DRect",
    "sampler3DRect", "sampler2DRectShadow", "sizeof", "cast", "namespace", "using"});
constexpr auto kReservedByTheBrowser =
    std::to_array<std::string_view>({"image1DShadow", "image2DShadow", "image1DArrayShadow", "image2DArrayShadow"});

template <size_t N>
bool listed(const std::array<std::string_view, N>& list, std::string_view word) {
  return std::find(list.begin(), list.end(), word) != list.end();
}

// Where the word's rule is written, or empty when the word is free.
std::string_view reserved_by(std::string_view word, GlslVersion version) {
  if (version == GlslVersion::es300) {
    if (listed(kReservedEs300, word)) return "GLSL ES 3.00 section 3.8";
    return {};
  }
  if (listed(kReservedEs100, word)) return "GLSL ES 1.00 section 3.7";
  if (listed(kReservedByTheBrowser, word)) return "reserved by GLSL ES 3.00; the browser reserves it in ES 1.00 too";
  return {};
}

std::string with_thousands(size_t n) {
  std::string digits = std::to_string(n);
  for (int at = static_cast<int>(digits.size()) - 3; at > 0; at -= 3) digits.insert(static_cast<size_t>(at), ",");
  return digits;
}

// The browser tokenizes the whole source before it preprocesses it: comments are not tokens,
// directives and skipped #if groups are.
void long_tokens(std::string_view glsl, std::vector<LexicalError>& out) {
  for (const GlslToken& t : tokens_of(glsl)) {
    if (t.text.size() <= kMaxTokenLength) continue;
    out.push_back({{t.line, t.column}, "'" + std::string(t.text.substr(0, 24)) + "...' : token too long: " + with_thousands(t.text.size()) +
                           " characters, and the browser reads at most 1,024 in a name or a number (WebGL 2 holds every "
                           "token, in either language, to GLSL ES 3.00's limit for names)"});
  }
}

// Words as the compiler's lexer meets them: after the preprocessor (a macro may bring one in, a
// skipped group none), directives aside, a field name after `.` never a keyword.
void reserved_words(std::string_view glsl, GlslVersion version, std::string_view preprocessed,
                    std::vector<LexicalError>& out) {
  const std::vector<std::string_view> lines = lines_of(preprocessed);
  for (size_t k = 0; k < lines.size(); ++k) {
    const std::string_view line = lines[k];
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string_view::npos || line[first] == '#') continue;
    char before = 0;  // the last character that was not a space
    for (size_t i = first; i < line.size();) {
      if (!identifier_start(line[i])) {
        if (!std::isspace(static_cast<unsigned char>(line[i]))) before = line[i];
        ++i;
        continue;
      }
      size_t end = i;
      while (end < line.size() && identifier_char(line[end])) ++end;
      const std::string_view word = line.substr(i, end - i);
      const std::string_view rule = before == '.' ? std::string_view{} : reserved_by(word, version);
      if (!rule.empty()) {
        const int number = static_cast<int>(k) + 1;
        const size_t column = whole_word(line_of(glsl, number), word);
        out.push_back({{number, column == std::string_view::npos ? 0 : static_cast<int>(column) + 1},
                       "'" + std::string(word) + "' : Illegal use of reserved word: GLSL ES keeps it for future use, "
                       "so it cannot name anything; choose another name (" + std::string(rule) + ")"});
      }
      before = 'a';
      i = end;
    }
  }
}

// The browser reads a #line number as a 32-bit int and refuses a larger one; the preprocessor
// here would wrap it round.
void line_numbers(std::string_view glsl, const GlslFacts& facts, std::vector<LexicalError>& out) {
  for (const auto& d : facts.line_directives) {
    for (const GlslToken& t : tokens_of(line_of(glsl, d.line))) {
      if (t.kind != GlslToken::Kind::number) continue;
      errno = 0;
      const std::string text(t.text);
      const unsigned long long value = std::strtoull(text.c_str(), nullptr, 0);
      if (errno == ERANGE || value > static_cast<unsigned long long>(INT_MAX))
        out.push_back({{d.line, t.column}, "'" + text + "' : integer overflow: a #line number is at most 2147483647"});
    }
  }
}

// `invariant a, b;`: the browser's grammar redeclares one name per `invariant` (GLSL ES 3.00
// section 4.6.1, `invariant IDENTIFIER`) and stops at the comma; glslang and Mesa take the list.
// A declaration (`invariant out vec4 a, b;`) is another form and stays.
void invariant_lists(std::string_view glsl, std::string_view preprocessed, std::vector<LexicalError>& out) {
  if (preprocessed.find("invariant") == std::string_view::npos) return;
  const std::vector<GlslToken> tokens = tokens_of(preprocessed);
  for (size_t i = 0; i + 2 < tokens.size(); ++i) {
    if (tokens[i].text != "invariant" || tokens[i + 1].kind != GlslToken::Kind::identifier || tokens[i + 2].text != ",")
      continue;
    const std::string_view line = line_of(glsl, tokens[i + 2].line);
    const size_t name = whole_word(line, tokens[i + 1].text);
    const size_t comma = name == std::string_view::npos ? name : line.find(',', name);
    out.push_back({{tokens[i + 2].line, comma == std::string_view::npos ? 0 : static_cast<int>(comma) + 1},
                   "',' : syntax error: `invariant` takes one name at a time, as in `invariant " +
                       std::string(tokens[i + 1].text) + ";` (GLSL ES 3.00 section 4.6.1)"});
  }
}

}  // namespace

std::vector<LexicalError> lexical_errors(std::string_view glsl, GlslVersion version, const GlslFacts& facts) {
  std::vector<LexicalError> out;
  long_tokens(glsl, out);
  if (!facts.preprocessed.empty()) reserved_words(glsl, version, facts.preprocessed, out);
  line_numbers(glsl, facts, out);
  if (!facts.preprocessed.empty()) invariant_lists(glsl, facts.preprocessed, out);
  return out;
}

void evaluate_line_directives(std::string& glsl, const GlslFacts& facts) {
  for (const auto& d : facts.line_directives) {
    const long number = std::strtol(d.evaluated.c_str() + 5, nullptr, 10);  // past "#line"
    replace_line(glsl, d.line, number < 0 ? std::string_view{} : std::string_view(d.evaluated));
  }
}

}  // namespace shadelab::shader
