#include "render/presets.h"

#include "core/check.h"
#include "core/embedded_files.h"

namespace shadelab::render {

namespace {
struct PresetEntry {
  const char* name;
  const char* description;
};
constexpr PresetEntry kPresets[] = {
    {"starter", "the handout's starter: flat normal colour, |N| normalised, computed per fragment"},
    {"smooth", "the warm-up: `flat` removed, the normal colour interpolated across each triangle"},
    {"gouraud", "checkpoint 1: the normal colour computed in the vertex shader and interpolated"},
    {"diffuse", "checkpoint 2: ambient + Lambert diffuse, per fragment"},
    {"specular", "checkpoint 3: ambient + diffuse + Phong specular (alpha 0.6, only where N.L > 0)"},
};

shader::ShaderFile load(const std::string& file) {
  const auto text = embedded_file("shaders/" + file);
  SHADELAB_CHECK(text.has_value(), "a preset's shader is not embedded");
  return {file, std::string(*text)};
}
}  // namespace

const std::vector<Preset>& presets() {
  static const std::vector<Preset> all = [] {
    std::vector<Preset> out;
    for (const auto& p : kPresets)
      out.push_back({p.name, p.description, load(std::string(p.name) + "_vert.js"), load(std::string(p.name) + "_frag.js")});
    return out;
  }();
  return all;
}

std::optional<Preset> find_preset(const std::string& name) {
  for (const auto& p : presets())
    if (p.name == name) return p;
  return std::nullopt;
}

}  // namespace shadelab::render
