#pragma once
// "a, b and c": a list as a sentence names it, for the messages students and TAs read.
#include <string>
#include <vector>

namespace shadelab {

inline std::string and_list(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  return out;
}

}  // namespace shadelab
