#pragma once
// Runtime configuration read from the environment (SHADELAB_*), used as flag defaults.
#include <cstdlib>
#include <string>

namespace shadelab::cli {

inline bool software_from_environment() {
  const char* v = std::getenv("SHADELAB_SOFTWARE");
  return v && std::string(v) != "0" && std::string(v) != "";
}

}  // namespace shadelab::cli
