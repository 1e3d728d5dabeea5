#include "scene_render/gpu_resources.h"

#include "gl/render_target.h"

#include <cmath>
#include <string>
#include <vector>

namespace shadelab::scene_render {

namespace {

// A new framebuffer, bound so the attachments that follow go to it.
gl::FramebufferName bound_framebuffer() {
  gl::FramebufferName fbo = gl::make_framebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
  return fbo;
}

GLuint gen_texture() {
  GLuint id = 0;
  glGenTextures(1, &id);
  return id;
}

// A 2D texture, clamped at its edges and bound, with `levels` levels of `format`.
gl::TextureName clamped_texture(int levels, GLenum format, int width, int height, GLenum min_filter, GLenum mag_filter) {
  gl::TextureName texture(gen_texture());
  glBindTexture(GL_TEXTURE_2D, texture.get());
  glTexStorage2D(GL_TEXTURE_2D, levels, format, width, height);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(min_filter));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(mag_filter));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return texture;
}

Status complete(const std::string& what) {
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status == GL_FRAMEBUFFER_COMPLETE) return Ok{};
  return make_error(ErrorCode::gl_error, "the driver rejected the " + what + " framebuffer (status 0x" +
                                             [&] { char b[16]; std::snprintf(b, sizeof b, "%x", status); return std::string(b); }() + ")");
}

// `fbo` becomes a new framebuffer drawing into `color` and, when given, testing against `depth`.
Status attach_renderbuffers(gl::FramebufferName& fbo, const gl::RenderbufferName& color, const gl::RenderbufferName* depth,
                            const std::string& what) {
  fbo = bound_framebuffer();
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color.get());
  if (depth) glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth->get());
  return complete(what);
}

}  // namespace

Expected<FrameTargets> FrameTargets::create(int width, int height, int samples) {
  FrameTargets t;
  t.width = width;
  t.height = height;
  t.hdr_color = gl::make_renderbuffer(GL_RGBA16F, width, height, samples);
  glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_SAMPLES, &t.samples);
  t.hdr_depth = gl::make_renderbuffer(GL_DEPTH_COMPONENT32F, width, height, samples);
  if (auto s = attach_renderbuffers(t.hdr_fbo, t.hdr_color, &t.hdr_depth, "HDR"); !s) return s.take_error();

  t.resolved = clamped_texture(1, GL_RGBA16F, width, height, GL_NEAREST, GL_NEAREST);
  t.resolve_fbo = bound_framebuffer();
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.resolved.get(), 0);
  if (auto s = complete("resolve"); !s) return s.take_error();

  t.display_color = gl::make_renderbuffer(GL_RGBA8, width, height, 0);
  if (auto s = attach_renderbuffers(t.display_fbo, t.display_color, nullptr, "display"); !s) return s.take_error();
  return t;
}

Expected<IdTarget> IdTarget::create(int width, int height) {
  IdTarget t;
  t.width = width;
  t.height = height;
  t.color = gl::make_renderbuffer(GL_RGBA8, width, height, 0);
  t.depth = gl::make_renderbuffer(GL_DEPTH_COMPONENT32F, width, height, 0);
  if (auto s = attach_renderbuffers(t.fbo, t.color, &t.depth, "object-id"); !s) return s.take_error();
  return t;
}

Expected<ShadowArray> ShadowArray::create(int size, int layers) {
  ShadowArray a;
  a.size = size;
  a.layers = layers;
  a.depth = gl::TextureName(gen_texture());
  glBindTexture(GL_TEXTURE_2D_ARRAY, a.depth.get());
  glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_DEPTH_COMPONENT32F, size, size, layers);
  GLuint samplers[2] = {0, 0};
  glGenSamplers(2, samplers);
  a.compare_sampler = gl::SamplerName(samplers[0]);
  a.raw_sampler = gl::SamplerName(samplers[1]);
  for (GLuint s : samplers) {
    glSamplerParameteri(s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  // Comparison with bilinear filtering: each tap is itself a 2x2 percentage-closer filter.
  glSamplerParameteri(samplers[0], GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glSamplerParameteri(samplers[0], GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glSamplerParameteri(samplers[0], GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glSamplerParameteri(samplers[0], GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glSamplerParameteri(samplers[1], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glSamplerParameteri(samplers[1], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glSamplerParameteri(samplers[1], GL_TEXTURE_COMPARE_MODE, GL_NONE);
  a.fbo = bound_framebuffer();
  a.bind_layer(0);
  if (auto s = complete("shadow"); !s) return s.take_error();
  return a;
}

void ShadowArray::bind_layer(int layer) const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
  glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, depth.get(), 0, layer);
  const GLenum none = GL_NONE;
  glDrawBuffers(1, &none);
  glReadBuffer(GL_NONE);
}

Expected<ReflectionMap> ReflectionMap::create(int size) {
  ReflectionMap r;
  r.size = size;
  r.levels = static_cast<int>(std::floor(std::log2(size))) + 1;
  r.color = clamped_texture(r.levels, GL_RGBA16F, size, size, GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
  r.fbo = bound_framebuffer();
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r.color.get(), 0);
  if (auto s = complete("reflection"); !s) return s.take_error();
  return r;
}

FilmicTextures FilmicTextures::upload(const image::FilmicTables& tables) {
  FilmicTextures f;
  constexpr int n = image::FilmicTables::kCubeSize, m = image::FilmicTables::kCurveSize;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  f.cube = gl::TextureName(gen_texture());
  glBindTexture(GL_TEXTURE_3D, f.cube.get());
  glTexStorage3D(GL_TEXTURE_3D, 1, GL_RGB16F, n, n, n);
  glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, n, n, n, GL_RGB, GL_FLOAT, tables.cube.data());
  for (GLenum p : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER}) glTexParameteri(GL_TEXTURE_3D, p, GL_LINEAR);
  for (GLenum p : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) glTexParameteri(GL_TEXTURE_3D, p, GL_CLAMP_TO_EDGE);

  f.curve = gl::TextureName(gen_texture());
  glBindTexture(GL_TEXTURE_2D, f.curve.get());
  // 32-bit: the curve is steep near black, and half floats would band there.
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGB32F, m, 1);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, m, 1, GL_RGB, GL_FLOAT, tables.curve.data());
  for (GLenum p : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER}) glTexParameteri(GL_TEXTURE_2D, p, GL_LINEAR);
  for (GLenum p : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T}) glTexParameteri(GL_TEXTURE_2D, p, GL_CLAMP_TO_EDGE);
  return f;
}

}  // namespace shadelab::scene_render
