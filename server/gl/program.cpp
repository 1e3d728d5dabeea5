#include "gl/program.h"

#include <algorithm>
#include <vector>

namespace shadelab::gl {

namespace {

std::string shader_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(std::max(length, 0)), '\0');
  if (length > 0) glGetShaderInfoLog(shader, length, nullptr, log.data());
  while (!log.empty() && log.back() == '\0') log.pop_back();
  return log;
}

std::string program_log(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(std::max(length, 0)), '\0');
  if (length > 0) glGetProgramInfoLog(program, length, nullptr, log.data());
  while (!log.empty() && log.back() == '\0') log.pop_back();
  return log;
}

ShaderName compile(GLenum type, const std::string& source, std::string& log, bool& ok) {
  ShaderName shader(glCreateShader(type));
  const char* text = source.c_str();
  const GLint length = static_cast<GLint>(source.size());
  glShaderSource(shader.get(), 1, &text, &length);
  glCompileShader(shader.get());
  GLint status = GL_FALSE;
  glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &status);
  ok = status == GL_TRUE;
  log = shader_log(shader.get());
  return shader;
}

enum class Interface { attribute, uniform };

std::vector<ActiveVariable> reflect(GLuint program, Interface which) {
  const bool attributes = which == Interface::attribute;
  GLint count = 0, max_length = 0;
  glGetProgramiv(program, attributes ? GL_ACTIVE_ATTRIBUTES : GL_ACTIVE_UNIFORMS, &count);
  glGetProgramiv(program, attributes ? GL_ACTIVE_ATTRIBUTE_MAX_LENGTH : GL_ACTIVE_UNIFORM_MAX_LENGTH, &max_length);
  std::vector<ActiveVariable> out;
  std::string buffer(static_cast<size_t>(std::max(max_length, 1)), '\0');
  for (GLint i = 0; i < count; ++i) {
    GLsizei length = 0;
    GLint size = 0;
    GLenum type = 0;
    if (attributes)
      glGetActiveAttrib(program, static_cast<GLuint>(i), max_length, &length, &size, &type, buffer.data());
    else
      glGetActiveUniform(program, static_cast<GLuint>(i), max_length, &length, &size, &type, buffer.data());
    ActiveVariable v;
    v.name.assign(buffer.data(), static_cast<size_t>(length));
    v.type = glsl_type(type);
    v.array_size = size;
    v.location = attributes ? glGetAttribLocation(program, v.name.c_str()) : glGetUniformLocation(program, v.name.c_str());
    out.push_back(std::move(v));
  }
  // Sorted by name so that reflection, and everything derived from it, is deterministic.
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  return out;
}

}  // namespace

Program Program::build(const std::string& vertex, const std::string& fragment,
                       std::span<const AttributeBinding> bindings, std::optional<BuildFailure>& failure) {
  Program result;
  std::string vertex_log, fragment_log;
  bool vertex_ok = false, fragment_ok = false;
  ShaderName vs = compile(GL_VERTEX_SHADER, vertex, vertex_log, vertex_ok);
  if (!vertex_ok) {
    failure = BuildFailure{BuildStage::vertex, vertex_log};
    return result;
  }
  ShaderName fs = compile(GL_FRAGMENT_SHADER, fragment, fragment_log, fragment_ok);
  if (!fragment_ok) {
    failure = BuildFailure{BuildStage::fragment, fragment_log};
    return result;
  }
  ProgramName program(glCreateProgram());
  glAttachShader(program.get(), vs.get());
  glAttachShader(program.get(), fs.get());
  for (const auto& b : bindings) glBindAttribLocation(program.get(), b.location, b.name);
  glLinkProgram(program.get());
  GLint status = GL_FALSE;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &status);
  std::string link_log = program_log(program.get());
  if (status != GL_TRUE) {
    failure = BuildFailure{BuildStage::link, link_log};
    return result;
  }
  glDetachShader(program.get(), vs.get());
  glDetachShader(program.get(), fs.get());
  result.vertex_log_ = std::move(vertex_log);
  result.fragment_log_ = std::move(fragment_log);
  result.link_log_ = std::move(link_log);
  result.attributes_ = reflect(program.get(), Interface::attribute);
  result.uniforms_ = reflect(program.get(), Interface::uniform);
  result.name_ = std::move(program);
  return result;
}

void Program::use() const { glUseProgram(name_.get()); }

void Program::zero_uniforms() const {
  std::vector<float> zeros;
  for (const auto& u : uniforms_) {
    zeros.assign(static_cast<size_t>(u.type.components) * static_cast<size_t>(std::max(1, u.array_size)), 0.0f);
    set_uniform(u, zeros);
  }
}

void Program::set_uniform(const ActiveVariable& u, std::span<const float> values) const {
  if (u.location < 0 || u.type.components == 0) return;
  const GLint loc = u.location;
  const auto count = static_cast<GLsizei>(values.size() / static_cast<size_t>(u.type.components));
  const float* f = values.data();
  switch (u.type.kind) {
    case ScalarKind::float_:
      switch (u.type.gl_enum) {
        case GL_FLOAT: glUniform1fv(loc, count, f); return;
        case GL_FLOAT_VEC2: glUniform2fv(loc, count, f); return;
        case GL_FLOAT_VEC3: glUniform3fv(loc, count, f); return;
        case GL_FLOAT_VEC4: glUniform4fv(loc, count, f); return;
        case GL_FLOAT_MAT2: glUniformMatrix2fv(loc, count, GL_FALSE, f); return;
        case GL_FLOAT_MAT3: glUniformMatrix3fv(loc, count, GL_FALSE, f); return;
        case GL_FLOAT_MAT4: glUniformMatrix4fv(loc, count, GL_FALSE, f); return;
        case GL_FLOAT_MAT2x3: glUniformMatrix2x3fv(loc, count, GL_FALSE, f); return;
        case GL_FLOAT_MAT2x4: glUniformMatrix2x4fv(loc, count, GL_FALSE, f); return;
        case GL_FLOAT_MAT3x2: glUniformMatrix3x2fv(loc, count, GL_FALSE, f); return;
        case GL_FLOAT_MAT3x4: glUniformMatrix3x4fv(loc, count, GL_FALSE, f); return;
        case GL_FLOAT_MAT4x2: glUniformMatrix4x2fv(loc, count, GL_FALSE, f); return;
        case GL_FLOAT_MAT4x3: glUniformMatrix4x3fv(loc, count, GL_FALSE, f); return;
        default: return;
      }
    case ScalarKind::int_:
    case ScalarKind::bool_:
    case ScalarKind::sampler: {
      // Values were checked to be integral (bool: 0 or 1) before they got here.
      std::vector<GLint> ints(values.begin(), values.end());
      switch (u.type.components) {
        case 1: glUniform1iv(loc, count, ints.data()); return;
        case 2: glUniform2iv(loc, count, ints.data()); return;
        case 3: glUniform3iv(loc, count, ints.data()); return;
        case 4: glUniform4iv(loc, count, ints.data()); return;
        default: return;
      }
    }
    case ScalarKind::uint_: {
      std::vector<GLuint> uints(values.begin(), values.end());
      switch (u.type.components) {
        case 1: glUniform1uiv(loc, count, uints.data()); return;
        case 2: glUniform2uiv(loc, count, uints.data()); return;
        case 3: glUniform3uiv(loc, count, uints.data()); return;
        case 4: glUniform4uiv(loc, count, uints.data()); return;
        default: return;
      }
    }
    case ScalarKind::other: return;
  }
}

}  // namespace shadelab::gl
