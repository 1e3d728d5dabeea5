#pragma once
// A non-indexed triangle list on the GPU: interleaved position (3 floats) and normal (3 floats),
// drawn with glDrawArrays(GL_TRIANGLES) as hw2.js does, so `flat` varyings take each triangle's
// last corner.
#include <span>

#include "gl/gl_name.h"

namespace shadelab::gl {

class MeshBuffer {
 public:
  // `interleaved` holds 6 floats per vertex, 3 vertices per triangle.
  static MeshBuffer upload(std::span<const float> interleaved);

  int vertex_count() const { return vertex_count_; }
  // Points the given attribute locations (-1: not used by the program) at the data and draws.
  void draw(int position_location, int normal_location) const;

 private:
  VertexArrayName vao_;
  BufferName vbo_;
  int vertex_count_ = 0;
};

}  // namespace shadelab::gl
