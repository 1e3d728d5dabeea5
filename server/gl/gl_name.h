#pragma once
// One move-only owner for every kind of GL name: copy deleted, move noexcept, the destructor
// deletes the name and never throws. A zero name owns nothing.
#include <GLES3/gl32.h>

#include <utility>

namespace shadelab::gl {

template <void (*Delete)(GLuint)>
class GlName {
 public:
  GlName() = default;
  explicit GlName(GLuint id) : id_(id) {}
  GlName(GlName&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  GlName& operator=(GlName&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  GlName(const GlName&) = delete;
  GlName& operator=(const GlName&) = delete;
  ~GlName() { reset(); }

  GLuint get() const { return id_; }
  explicit operator bool() const { return id_ != 0; }

 private:
  void reset() {
    if (id_ != 0) Delete(id_);
    id_ = 0;
  }
  GLuint id_ = 0;
};

namespace detail {
inline void delete_buffer(GLuint id) { glDeleteBuffers(1, &id); }
inline void delete_vertex_array(GLuint id) { glDeleteVertexArrays(1, &id); }
inline void delete_framebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
inline void delete_renderbuffer(GLuint id) { glDeleteRenderbuffers(1, &id); }
inline void delete_shader(GLuint id) { glDeleteShader(id); }
inline void delete_program(GLuint id) { glDeleteProgram(id); }
inline void delete_texture(GLuint id) { glDeleteTextures(1, &id); }
inline void delete_sampler(GLuint id) { glDeleteSamplers(1, &id); }
inline void delete_query(GLuint id) { glDeleteQueries(1, &id); }
}  // namespace detail

using BufferName = GlName<detail::delete_buffer>;
using VertexArrayName = GlName<detail::delete_vertex_array>;
using FramebufferName = GlName<detail::delete_framebuffer>;
using RenderbufferName = GlName<detail::delete_renderbuffer>;
using ShaderName = GlName<detail::delete_shader>;
using ProgramName = GlName<detail::delete_program>;
using TextureName = GlName<detail::delete_texture>;
using SamplerName = GlName<detail::delete_sampler>;

}  // namespace shadelab::gl
