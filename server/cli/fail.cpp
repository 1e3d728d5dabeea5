#include <iostream>

#include "cli/commands.h"

namespace shadelab::cli {

int fail(const Error& e) {
  for (const auto& d : e.diagnostics) std::cerr << d.format() << "\n";
  std::cerr << "error: " << e.message << " [" << to_string(e.code) << "]\n";
  if (e.diagnostics.empty() && !e.driver_log.empty()) std::cerr << e.driver_log << "\n";
  return 1;
}

}  // namespace shadelab::cli
