#include "gl/mesh_buffer.h"

#include <algorithm>
#include <bit>
#include <cstring>

namespace shadelab::gl {

namespace {

constexpr size_t kFloatsPerVertex = 6;

std::uint64_t vertex_hash(const float* v) {
  std::uint32_t bits[kFloatsPerVertex];
  std::memcpy(bits, v, sizeof bits);
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  for (std::uint32_t b : bits) h = (h ^ b) * 0xff51afd7ed558ccdull, h ^= h >> 29;
  return h;
}

}  // namespace

// Open addressing on the vertices' bits (so -0.0 and 0.0, or two NaNs, stay distinct vertices,
// as they are distinct inputs to a shader): a table twice the corner count, linear probing.
IndexedCorners index_corners(std::span<const float> interleaved) {
  const size_t corners = interleaved.size() / kFloatsPerVertex;
  IndexedCorners out;
  out.indices.reserve(corners);
  const size_t table_size = std::bit_ceil(std::max<size_t>(16, corners * 2));
  std::vector<std::uint32_t> table(table_size, 0);  // vertex index + 1; 0: empty
  for (size_t c = 0; c < corners; ++c) {
    const float* corner = interleaved.data() + c * kFloatsPerVertex;
    size_t slot = vertex_hash(corner) & (table_size - 1);
    while (true) {
      const std::uint32_t entry = table[slot];
      if (entry == 0) {
        const auto index = static_cast<std::uint32_t>(out.vertices.size() / kFloatsPerVertex);
        table[slot] = index + 1;
        out.vertices.insert(out.vertices.end(), corner, corner + kFloatsPerVertex);
        out.indices.push_back(index);
        break;
      }
      if (std::memcmp(&out.vertices[(entry - 1) * kFloatsPerVertex], corner, kFloatsPerVertex * sizeof(float)) == 0) {
        out.indices.push_back(entry - 1);
        break;
      }
      slot = (slot + 1) & (table_size - 1);
    }
  }
  return out;
}

MeshBuffer MeshBuffer::upload(std::span<const float> interleaved) {
  const IndexedCorners indexed = index_corners(interleaved);
  MeshBuffer m;
  GLuint vao = 0, buffers[2] = {0, 0};
  glGenVertexArrays(1, &vao);
  glGenBuffers(2, buffers);
  m.vao_ = VertexArrayName(vao);
  m.vbo_ = BufferName(buffers[0]);
  m.ibo_ = BufferName(buffers[1]);
  glBindVertexArray(vao);
  glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(indexed.vertices.size() * sizeof(float)), indexed.vertices.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers[1]);  // part of the vertex array's state
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indexed.indices.size() * sizeof(std::uint32_t)), indexed.indices.data(),
               GL_STATIC_DRAW);
  glBindVertexArray(0);
  m.corner_count_ = static_cast<int>(indexed.indices.size());
  m.bytes_ = indexed.vertices.size() * sizeof(float) + indexed.indices.size() * sizeof(std::uint32_t);
  return m;
}

void MeshBuffer::draw(int position_location, int normal_location) const {
  glBindVertexArray(vao_.get());
  glBindBuffer(GL_ARRAY_BUFFER, vbo_.get());
  constexpr GLsizei stride = kFloatsPerVertex * sizeof(float);
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
  glDrawElements(GL_TRIANGLES, corner_count_, GL_UNSIGNED_INT, nullptr);
}

}  // namespace shadelab::gl
