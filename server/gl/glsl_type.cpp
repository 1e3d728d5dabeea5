#include "gl/glsl_type.h"

#include <GLES3/gl32.h>

namespace shadelab::gl {

namespace {
constexpr GlslType kTypes[] = {
    {GL_FLOAT, "float", ScalarKind::float_, 1, false},
    {GL_FLOAT_VEC2, "vec2", ScalarKind::float_, 2, false},
    {GL_FLOAT_VEC3, "vec3", ScalarKind::float_, 3, false},
    {GL_FLOAT_VEC4, "vec4", ScalarKind::float_, 4, false},
    {GL_INT, "int", ScalarKind::int_, 1, false},
    {GL_INT_VEC2, "ivec2", ScalarKind::int_, 2, false},
    {GL_INT_VEC3, "ivec3", ScalarKind::int_, 3, false},
    {GL_INT_VEC4, "ivec4", ScalarKind::int_, 4, false},
    {GL_UNSIGNED_INT, "uint", ScalarKind::uint_, 1, false},
    {GL_UNSIGNED_INT_VEC2, "uvec2", ScalarKind::uint_, 2, false},
    {GL_UNSIGNED_INT_VEC3, "uvec3", ScalarKind::uint_, 3, false},
    {GL_UNSIGNED_INT_VEC4, "uvec4", ScalarKind::uint_, 4, false},
    {GL_BOOL, "bool", ScalarKind::bool_, 1, false},
    {GL_BOOL_VEC2, "bvec2", ScalarKind::bool_, 2, false},
    {GL_BOOL_VEC3, "bvec3", ScalarKind::bool_, 3, false},
    {GL_BOOL_VEC4, "bvec4", ScalarKind::bool_, 4, false},
    {GL_FLOAT_MAT2, "mat2", ScalarKind::float_, 4, true},
    {GL_FLOAT_MAT3, "mat3", ScalarKind::float_, 9, true},
    {GL_FLOAT_MAT4, "mat4", ScalarKind::float_, 16, true},
    {GL_FLOAT_MAT2x3, "mat2x3", ScalarKind::float_, 6, true},
    {GL_FLOAT_MAT2x4, "mat2x4", ScalarKind::float_, 8, true},
    {GL_FLOAT_MAT3x2, "mat3x2", ScalarKind::float_, 6, true},
    {GL_FLOAT_MAT3x4, "mat3x4", ScalarKind::float_, 12, true},
    {GL_FLOAT_MAT4x2, "mat4x2", ScalarKind::float_, 8, true},
    {GL_FLOAT_MAT4x3, "mat4x3", ScalarKind::float_, 12, true},
    {GL_SAMPLER_2D, "sampler2D", ScalarKind::sampler, 1, false},
    {GL_SAMPLER_3D, "sampler3D", ScalarKind::sampler, 1, false},
    {GL_SAMPLER_CUBE, "samplerCube", ScalarKind::sampler, 1, false},
    {GL_SAMPLER_2D_SHADOW, "sampler2DShadow", ScalarKind::sampler, 1, false},
    {GL_SAMPLER_2D_ARRAY, "sampler2DArray", ScalarKind::sampler, 1, false},
};
}  // namespace

GlslType glsl_type(unsigned gl_enum) {
  for (const auto& t : kTypes)
    if (t.gl_enum == gl_enum) return t;
  return GlslType{gl_enum, "unknown", ScalarKind::other, 0, false};
}

}  // namespace shadelab::gl
