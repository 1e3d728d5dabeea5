#pragma once
// Files compiled into the binary at build time (shaders/*.js, assets/*.obj), so the executable
// needs no install tree to find its presets and built-in meshes.
#include <optional>
#include <string_view>
#include <vector>

namespace shadelab {

struct EmbeddedFile {
  std::string_view path;  // relative to the repository root: "shaders/phong_frag.js"
  std::string_view bytes;
};

std::optional<std::string_view> embedded_file(std::string_view path);
const std::vector<EmbeddedFile>& embedded_files();

}  // namespace shadelab
