#include "gl/mesh_buffer.h"

namespace shadelab::gl {

MeshBuffer MeshBuffer::upload(std::span<const float> interleaved) {
  MeshBuffer m;
  GLuint vao = 0, vbo = 0;
  glGenVertexArrays(1, &vao);
  glGenBuffers(1, &vbo);
  m.vao_ = VertexArrayName(vao);
  m.vbo_ = BufferName(vbo);
  glBindVertexArray(vao);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(interleaved.size_bytes()), interleaved.data(), GL_STATIC_DRAW);
  glBindVertexArray(0);
  m.vertex_count_ = static_cast<int>(interleaved.size() / 6);
  return m;
}

void MeshBuffer::draw(int position_location, int normal_location) const {
  glBindVertexArray(vao_.get());
  glBindBuffer(GL_ARRAY_BUFFER, vbo_.get());
  constexpr GLsizei stride = 6 * sizeof(float);
  // Locations a previous program enabled must not leak into this draw.
  GLint max_attribs = 0;
  glGetIntegerv(GL_MAX_VERTEX_ATTRIBS, &max_attribs);
  for (GLint i = 0; i < max_attribs; ++i) glDisableVertexAttribArray(static_cast<GLuint>(i));
  // Three components are supplied; GL fills w = 1 for a vec4 attribute, as WebGL does.
  if (position_location >= 0) {
    glEnableVertexAttribArray(static_cast<GLuint>(position_location));
    glVertexAttribPointer(static_cast<GLuint>(position_location), 3, GL_FLOAT, GL_FALSE, stride, nullptr);
  }
  if (normal_location >= 0) {
    glEnableVertexAttribArray(static_cast<GLuint>(normal_location));
    glVertexAttribPointer(static_cast<GLuint>(normal_location), 3, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(3 * sizeof(float)));
  }
  glDrawArrays(GL_TRIANGLES, 0, vertex_count_);
}

}  // namespace shadelab::gl
