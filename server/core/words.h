#pragma once
// Lists and shares in words, for the messages students and TAs read: "a, b and c" as a sentence names them,
// "a, b, c" as a listing does.
#include <cstdio>
#include <string>
#include <vector>

namespace shadelab {

inline std::string and_list(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  return out;
}

// A share as a percentage with `decimals` places: percent(0.372, 1) is "37.2%".
inline std::string percent(double share, int decimals = 0) {
  char out[32];
  std::snprintf(out, sizeof out, "%.*f%%", decimals, 100 * share);
  return out;
}

inline std::string comma_list(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i == 0 ? "" : ", ") + items[i];
  return out;
}

}  // namespace shadelab
