#include "grade/starter_constants.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <regex>

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

std::vector<ConstantFinding> changed_starter_constants(const std::vector<StarterConstant>& constants, const std::string& source) {
  std::vector<ConstantFinding> out;
  const std::string code = without_comments(source);
  for (const auto& c : constants) {
    // `variable` comes from the course profile, which allows only a GLSL identifier there.
    const std::regex assigned("\\b" + c.variable + "\\s*=\\s*([-+]?(?:[0-9]+\\.?[0-9]*|\\.[0-9]+)(?:[eE][-+]?[0-9]+)?)\\s*;");
    std::smatch m;
    if (!std::regex_search(code, m, assigned)) continue;
    const std::string literal = m[1].str();
    const double found = std::strtod(literal.c_str(), nullptr);
    if (found == c.value) continue;
    out.push_back({c.variable, "your shader's " + c.meaning + " is " + literal + "; the course's starter uses " + glsl_number(c.value) +
                                   " (" + c.variable + ")"});
  }
  return out;
}

}  // namespace shadelab::grade
