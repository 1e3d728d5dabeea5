#include "scene_render/scene_program.h"

#include "core/embedded_files.h"

namespace shadelab::scene_render {

std::string ShaderVariant::key() const {
  std::string k = vertex + "|" + fragment;
  for (const auto& [name, value] : defines) k += "|" + name + "=" + value;
  return k;
}

namespace {
Expected<std::string> source(const std::string& file, const ShaderVariant& variant) {
  const auto text = embedded_file("shaders/scene/" + file);
  if (!text) return make_error(ErrorCode::io_error, "shaders/scene/" + file + " is not compiled into this binary");
  std::string out = "#version 300 es\n";
  for (const auto& [name, value] : variant.defines) out += "#define " + name + " " + value + "\n";
  out += "#line 1\n";
  out += *text;
  return out;
}
}  // namespace

Expected<SceneProgram> SceneProgram::build(const ShaderVariant& variant) {
  auto vs = source(variant.vertex, variant);
  if (!vs) return vs.take_error();
  auto fs = source(variant.fragment, variant);
  if (!fs) return fs.take_error();
  std::optional<gl::BuildFailure> failure;
  SceneProgram p;
  p.program_ = gl::Program::build(*vs, *fs, {}, failure);
  // Our own shaders: a failure here is a bug or a driver without what GLSL ES 3.00 promises.
  if (failure)
    return Error{ErrorCode::gl_error, "the scene shader " + variant.key() + " did not build on this driver", {}, failure->log};
  return p;
}

GLint SceneProgram::uniform(const char* name) const {
  auto it = locations_.find(name);
  if (it != locations_.end()) return it->second;
  const GLint location = glGetUniformLocation(program_.id(), name);
  locations_.emplace(name, location);
  return location;
}

Expected<const SceneProgram*> ProgramCache::get(const ShaderVariant& variant) {
  const std::string key = variant.key();
  if (auto it = programs_.find(key); it != programs_.end()) return &it->second;
  auto built = SceneProgram::build(variant);
  if (!built) return built.take_error();
  return &programs_.emplace(key, std::move(*built)).first->second;
}

}  // namespace shadelab::scene_render
