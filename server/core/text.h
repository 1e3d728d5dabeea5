#pragma once
// Small text helpers the readers of what people wrote share (notebooks, page scripts).
#include <algorithm>
#include <cctype>
#include <string>

namespace shadelab {

inline std::string lower_case(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Without the spaces, tabs and line ends around it.
inline std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

}  // namespace shadelab
