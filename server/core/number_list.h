#pragma once
// "1,2.5,-3": comma-separated numbers, as query parameters (/api/dolly) and flags (--uniform)
// take them. Every item must be a whole finite number; the error names `what` and the item.
#include <string>
#include <string_view>
#include <vector>

#include "core/expected.h"

namespace shadelab {

struct NumberListOptions {
  bool booleans = false;  // "true" and "false" count as 1 and 0 (GLSL bool uniforms)
  size_t count = 0;       // exactly this many numbers; 0 for any number of them
};

Expected<std::vector<double>> parse_number_list(std::string_view text, std::string_view what, const NumberListOptions& options = {});

}  // namespace shadelab
