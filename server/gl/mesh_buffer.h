#pragma once
// A triangle list on the GPU, drawn as hw2.js draws it: triangle after triangle in the mesh's
// order, each corner an interleaved position (3 floats) and normal (3 floats), so `flat`
// varyings take each triangle's last corner.
//
// Corners that are the same vertex (bit-identical position and normal) are stored once and drawn
// through an index buffer: the primitives, their order and every attribute the shaders see are
// those of the page's glDrawArrays, but the driver shades a shared vertex once where its vertex
// cache still holds it (a closed mesh shares each vertex among ~6 triangles). On llvmpipe that is
// most of a large mesh's cost per frame (docs/performance-log.md, the triangle-count table).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "gl/gl_name.h"

namespace shadelab::gl {

// The distinct vertices of a corner list and, for each corner, its vertex's index.
struct IndexedCorners {
  std::vector<float> vertices;          // 6 floats per distinct vertex, in order of first use
  std::vector<std::uint32_t> indices;  // one per corner
};
IndexedCorners index_corners(std::span<const float> interleaved);

class MeshBuffer {
 public:
  // `interleaved` holds 6 floats per corner, 3 corners per triangle.
  static MeshBuffer upload(std::span<const float> interleaved);

  // Points the given attribute locations (-1: not used by the program) at the data and draws.
  void draw(int position_location, int normal_location) const;
  // The vertex and index buffers' sizes.
  std::size_t bytes() const { return bytes_; }

 private:
  VertexArrayName vao_;
  BufferName vbo_, ibo_;
  int corner_count_ = 0;  // 3 per triangle
  std::size_t bytes_ = 0;
};

}  // namespace shadelab::gl
