#include "shader/glsl_lines.h"

#include <algorithm>
#include <cctype>

namespace shadelab::shader {

std::vector<std::string_view> lines_of(std::string_view text) {
  std::vector<std::string_view> lines;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t end = text.find('\n', start);
    lines.push_back(text.substr(start, end == std::string_view::npos ? text.size() - start : end - start));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return lines;
}

std::string_view line_of(std::string_view text, int number) {
  size_t start = 0;
  for (int k = 1; k < number; ++k) {
    start = text.find('\n', start);
    if (start == std::string_view::npos) return {};
    ++start;
  }
  const size_t end = text.find('\n', start);
  return text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
}

bool identifier_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

size_t whole_word(std::string_view line, std::string_view name) {
  for (size_t at = line.find(name); at != std::string_view::npos; at = line.find(name, at + 1)) {
    const bool starts = at == 0 || !identifier_char(line[at - 1]);
    const bool ends = at + name.size() >= line.size() || !identifier_char(line[at + name.size()]);
    if (starts && ends) return at;
  }
  return std::string_view::npos;
}

namespace {

bool digit(char c) { return std::isdigit(static_cast<unsigned char>(c)); }

size_t token_end(std::string_view text, size_t i) {
  const bool identifier = identifier_start(text[i]);
  if (!identifier && !digit(text[i]) && text[i] != '.') return i + 1;
  size_t end = i + 1;
  while (end < text.size()) {
    const char n = text[end];
    const bool exponent_sign = !identifier && (n == '+' || n == '-') && (text[end - 1] == 'e' || text[end - 1] == 'E');
    if (!(identifier_char(n) || (!identifier && n == '.') || exponent_sign)) break;
    ++end;
  }
  return end;
}

}  // namespace

std::vector<GlslToken> tokens_of(std::string_view text) {
  std::vector<GlslToken> out;
  int line = 1;
  size_t line_start = 0;
  const auto newlines_until = [&](size_t end, size_t from) {
    for (size_t k = from; k < end; ++k)
      if (text[k] == '\n') ++line, line_start = k + 1;
  };
  for (size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      newlines_until(i + 1, i);
      ++i;
    } else if (text.compare(i, 2, "//") == 0) {
      i = std::min(text.find('\n', i), text.size());
    } else if (text.compare(i, 2, "/*") == 0) {
      const size_t close = text.find("*/", i + 2);
      const size_t end = close == std::string_view::npos ? text.size() : close + 2;
      newlines_until(end, i);
      i = end;
    } else {
      const bool number = digit(c) || (c == '.' && i + 1 < text.size() && digit(text[i + 1]));
      const size_t end = number || identifier_start(c) ? token_end(text, i) : i + 1;
      const auto kind = number ? GlslToken::Kind::number
                               : identifier_start(c) ? GlslToken::Kind::identifier : GlslToken::Kind::punctuation;
      out.push_back({kind, text.substr(i, end - i), line, static_cast<int>(i - line_start) + 1});
      i = end;
    }
  }
  return out;
}

void replace_line(std::string& glsl, int number, std::string_view with) {
  const std::string_view line = line_of(glsl, number);
  if (line.data() == nullptr || (line.empty() && with.empty())) return;
  const size_t start = static_cast<size_t>(line.data() - glsl.data());
  glsl.replace(start, line.size(), with);
}

}  // namespace shadelab::shader
