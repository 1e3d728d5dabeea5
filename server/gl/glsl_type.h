#pragma once
// GLSL types as the reflection of a linked program reports them, without GL headers, so the
// render layer can type-check values against them.
#include <string_view>

namespace shadelab::gl {

enum class ScalarKind { float_, int_, uint_, bool_, sampler, other };

struct GlslType {
  unsigned gl_enum = 0;          // the GL type enum, for the upload
  std::string_view name;         // "vec4", "mat4", ...
  ScalarKind kind = ScalarKind::other;
  int components = 0;            // 4 for vec4, 16 for mat4; 1 for samplers
  bool matrix = false;
};

// The type for a GL type enum; kind other / name "unknown" for types we do not feed.
GlslType glsl_type(unsigned gl_enum);

}  // namespace shadelab::gl
