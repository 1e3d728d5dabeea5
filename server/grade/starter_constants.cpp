#include "grade/starter_constants.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cctype>
#include <optional>

namespace shadelab::grade {

namespace {

// 6 -> "6.0", 0.6 -> "0.6": as a GLSL float literal is written.
std::string glsl_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, v == std::floor(v) && std::abs(v) < 1e9 ? "%.1f" : "%g", v);
  return buf;
}

}  // namespace

std::string without_comments(const std::string& s) {
  std::string out = s;
  for (size_t i = 0; i + 1 < out.size(); ++i) {
    if (out[i] == '/' && out[i + 1] == '/') {
      while (i < out.size() && out[i] != '\n') out[i++] = ' ';
    } else if (out[i] == '/' && out[i + 1] == '*') {
      const size_t end = out.find("*/", i + 2);
      const size_t stop = end == std::string::npos ? out.size() : end + 2;
      for (; i < stop; ++i)
        if (out[i] != '\n') out[i] = ' ';
      --i;
    }
  }
  return out;
}

namespace {

bool identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

size_t skip_spaces(const std::string& s, size_t at) {
  while (at < s.size() && std::isspace(static_cast<unsigned char>(s[at]))) ++at;
  return at;
}

// The literal assigned to `variable` at its first `variable = NUMBER ;` in `code`, if any. A
// linear scan: a student's source is a stranger's bytes, and std::regex recurses per character.
std::optional<std::string> assigned_literal(const std::string& code, const std::string& variable) {
  for (size_t at = code.find(variable); at != std::string::npos; at = code.find(variable, at + 1)) {
    const size_t end = at + variable.size();
    if ((at > 0 && identifier_char(code[at - 1])) || (end < code.size() && identifier_char(code[end]))) continue;
    size_t i = skip_spaces(code, end);
    if (i >= code.size() || code[i] != '=' || (i + 1 < code.size() && code[i + 1] == '=')) continue;
    i = skip_spaces(code, i + 1);
    const size_t number = i;
    if (i < code.size() && (code[i] == '-' || code[i] == '+')) ++i;
    while (i < code.size() && (std::isdigit(static_cast<unsigned char>(code[i])) || code[i] == '.')) ++i;
    if (i < code.size() && (code[i] == 'e' || code[i] == 'E')) {
      ++i;
      if (i < code.size() && (code[i] == '-' || code[i] == '+')) ++i;
      while (i < code.size() && std::isdigit(static_cast<unsigned char>(code[i]))) ++i;
    }
    const std::string literal = code.substr(number, i - number);
    if (literal.find_first_of("0123456789") == std::string::npos) continue;
    if (const size_t semicolon = skip_spaces(code, i); semicolon < code.size() && code[semicolon] == ';') return literal;
  }
  return std::nullopt;
}

}  // namespace

std::vector<ConstantFinding> changed_starter_constants(const std::vector<StarterConstant>& constants, const std::string& source) {
  std::vector<ConstantFinding> out;
  const std::string code = without_comments(source);
  for (const auto& c : constants) {
    const auto literal = assigned_literal(code, c.variable);
    if (!literal) continue;
    const double found = std::strtod(literal->c_str(), nullptr);
    if (found == c.value) continue;
    out.push_back({c.variable, found, "your shader's " + c.meaning + " is " + *literal + "; the course's starter uses " + glsl_number(c.value) +
                                   " (" + c.variable + ")"});
  }
  return out;
}

}  // namespace shadelab::grade
