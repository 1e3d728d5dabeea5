#include "shader/driver_rewrites.h"

#include <algorithm>
#include <regex>
#include <span>

#include "shader/glsl_lines.h"

namespace shadelab::shader {

namespace {

bool basic_type_word(std::string_view w) {
  static const std::regex type(R"((float|int|uint|bool|[ibu]?vec[234]|mat[234](x[234])?|[iu]?sampler\w+))");
  return std::regex_match(w.begin(), w.end(), type);
}

bool same_words(std::span<const GlslToken> a, std::span<const GlslToken> b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const GlslToken& x, const GlslToken& y) { return x.text == y.text; });
}

}  // namespace

// `layout(std140) uniform;` after the directives (#version, #extension), then `#line` gives the
// next line the number it had: GLSL ES 3.00 section 3.4 numbers the line after `#line N` as N.
void default_to_std140(std::string& glsl, const GlslFacts& facts) {
  int after = 1;
  for (const auto& d : facts.extensions) after = std::max(after, d.line);
  const std::string_view line = line_of(glsl, after);
  const size_t end = static_cast<size_t>(line.data() - glsl.data()) + line.size();
  const std::string insert = "layout(std140) uniform;\n#line " + std::to_string(after + 1) + "\n";
  if (end >= glsl.size()) glsl += "\n" + insert;
  else glsl.insert(end + 1, insert);
}

// `case 0: int;` as a label's last statement: the browser takes the empty declaration as the
// statement a label needs, NVIDIA's driver refuses it ("no statement at the end of a switch
// block"; measured on an H100, docs/webgl-rules.md). After a label, inside a function, the
// declaration declares nothing, so its words are blanked and `case 0: ;` is the same program,
// every column kept. Read from the preprocessor's output (no comments, #if resolved); a form
// a macro made is not on the source line and is left as it is.
void blank_empty_declarations_after_labels(std::string& glsl, const GlslFacts& facts) {
  if (facts.preprocessed.find("switch") == std::string::npos) return;  // no label, and no tokens to read on every compile
  const auto tokens = tokens_of(facts.preprocessed);
  for (size_t i = 1; i + 1 < tokens.size(); ++i) {
    if (tokens[i - 1].text != ":") continue;
    size_t type = i;
    if (tokens[i].text == "lowp" || tokens[i].text == "mediump" || tokens[i].text == "highp") ++type;
    if (type + 1 >= tokens.size() || !basic_type_word(tokens[type].text) || tokens[type + 1].text != ";") continue;
    const int line = tokens[i].line;
    if (tokens[type + 1].line != line) continue;
    // The same words on the student's line (glslang's output spaces them its own way), or a macro
    // or a comment is in the way and the line is left alone.
    const auto first = std::find_if(tokens.begin(), tokens.end(), [&](const GlslToken& t) { return t.line == line; });
    const auto last = std::find_if(first, tokens.end(), [&](const GlslToken& t) { return t.line != line; });
    const std::string_view source_line = line_of(glsl, line);
    const auto source_tokens = tokens_of(source_line);
    if (!same_words({first, last}, source_tokens)) continue;
    const size_t line_start = static_cast<size_t>(source_line.data() - glsl.data());
    for (size_t t = i; t <= type; ++t) {
      const GlslToken& word = source_tokens[t - static_cast<size_t>(first - tokens.begin())];
      glsl.replace(line_start + static_cast<size_t>(word.column - 1), word.text.size(), word.text.size(), ' ');
    }
  }
}

// Mesa counts a `#pragma` as code before `#extension`, the browser does not: a hint
// (`optimize`, `debug`, one it does not know) before an extension the driver still gets is left
// out; `STDGL invariant(all)` changes the program and stays.
void blank_hints_before(std::string& glsl, const GlslFacts& facts, int last_extension) {
  const auto lines = lines_of(facts.preprocessed);
  for (int n = 1; n < last_extension && n <= static_cast<int>(lines.size()); ++n) {
    const std::string_view line = lines[static_cast<size_t>(n - 1)];
    if (line.rfind("#pragma", 0) == 0 && line.find("shadelab_extension") == std::string_view::npos &&
        std::find(facts.invariant_all_pragmas.begin(), facts.invariant_all_pragmas.end(), n) == facts.invariant_all_pragmas.end())
      replace_line(glsl, n, "");
  }
}

}  // namespace shadelab::shader
