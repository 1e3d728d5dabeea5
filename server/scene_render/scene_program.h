#pragma once
// The scene shaders (shaders/scene/*.vert|frag, compiled into the binary), built per feature set:
// a scene pays only for the features it uses, and each variant is compiled once per worker.
#include <map>
#include <string>
#include <unordered_map>

#include "core/expected.h"
#include "gl/program.h"

namespace shadelab::scene_render {

inline constexpr int kMaxLights = 8;
inline constexpr int kMaxShadowViews = 16;

struct ShaderVariant {
  std::string vertex = "scene.vert", fragment = "scene.frag";
  std::map<std::string, std::string> defines;  // ordered: the key is stable
  std::string key() const;
};

// A built program with its uniform locations looked up once by name.
class SceneProgram {
 public:
  static Expected<SceneProgram> build(const ShaderVariant& variant);
  void use() const { program_.use(); }
  GLint uniform(const char* name) const;  // -1 when the variant does not have it

 private:
  gl::Program program_;
  mutable std::unordered_map<std::string, GLint> locations_;
};

class ProgramCache {
 public:
  Expected<const SceneProgram*> get(const ShaderVariant& variant);
  size_t size() const { return programs_.size(); }

 private:
  std::map<std::string, SceneProgram> programs_;
};

}  // namespace shadelab::scene_render
