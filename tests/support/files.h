#pragma once
// A whole file as bytes ("" when it cannot be read): what the tests compare outputs with.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace shadelab::testkit {

// Where the repository's test data is read from: the checkout the tests were built in, or
// SHADELAB_TEST_DATA where a packed build runs on another machine (tools/gpu_check/).
inline std::filesystem::path source_dir() {
  const char* packed = std::getenv("SHADELAB_TEST_DATA");
  return packed && *packed ? std::filesystem::path(packed) : std::filesystem::path(SHADELAB_SOURCE_DIR);
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

}  // namespace shadelab::testkit
