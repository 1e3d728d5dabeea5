#include "core/number_list.h"

#include <cmath>
#include <cstdlib>

namespace shadelab {

Expected<std::vector<double>> parse_number_list(std::string_view text, std::string_view what, const NumberListOptions& options) {
  std::vector<double> out;
  size_t pos = 0;
  while (pos <= text.size()) {
    const size_t comma = std::min(text.find(',', pos), text.size());
    const std::string item(text.substr(pos, comma - pos));
    pos = comma + 1;
    if (options.booleans && (item == "true" || item == "false")) {
      out.push_back(item == "true" ? 1.0 : 0.0);
      continue;
    }
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v))
      return make_error(ErrorCode::invalid_argument, std::string(what) + ": '" + item + "' is not a number");
    out.push_back(v);
  }
  if (options.count && out.size() != options.count)
    return make_error(ErrorCode::invalid_argument, std::string(what) + ": expected " + std::to_string(options.count) + " numbers");
  return out;
}

}  // namespace shadelab
