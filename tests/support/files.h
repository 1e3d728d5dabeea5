#pragma once
// A whole file as bytes ("" when it cannot be read): what the tests compare outputs with.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace shadelab::testkit {

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

}  // namespace shadelab::testkit
