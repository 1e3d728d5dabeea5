#pragma once
// Lists in words, for the messages students and TAs read: "a, b and c" as a sentence names them,
// "a, b, c" as a listing does.
#include <string>
#include <vector>

namespace shadelab {

inline std::string and_list(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  return out;
}

inline std::string comma_list(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i == 0 ? "" : ", ") + items[i];
  return out;
}

}  // namespace shadelab
