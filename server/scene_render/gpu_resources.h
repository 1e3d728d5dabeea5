#pragma once
// The GL objects the scene passes draw into and read from, each a move-only owner made once and
// kept while its size still fits.
#include <optional>

#include "core/expected.h"
#include "gl/gl_name.h"
#include "image/view_transform.h"

namespace shadelab::scene_render {

// The main pass: HDR colour (RGBA16F, multisampled when asked) with a float depth buffer; its
// resolve into a texture the view pass samples; the display-referred RGBA8 image.
struct FrameTargets {
  int width = 0, height = 0, samples = 0;
  gl::RenderbufferName hdr_color, hdr_depth, display_color;
  gl::FramebufferName hdr_fbo, resolve_fbo, display_fbo;
  gl::TextureName resolved;

  static Expected<FrameTargets> create(int width, int height, int samples);
};

// RGBA8 + depth, single-sampled: the object-id and guard-band passes.
struct IdTarget {
  int width = 0, height = 0;
  gl::RenderbufferName color, depth;
  gl::FramebufferName fbo;

  static Expected<IdTarget> create(int width, int height);
};

// One depth layer per shadow view, read with and without comparison.
struct ShadowArray {
  int size = 0, layers = 0;
  gl::TextureName depth;
  gl::FramebufferName fbo;
  gl::SamplerName compare_sampler, raw_sampler;

  static Expected<ShadowArray> create(int size, int layers);
  void bind_layer(int layer) const;
};

// The ground's radiance from above, mipmapped so rough reflections read a blurred level.
struct ReflectionMap {
  int size = 0, levels = 1;
  gl::TextureName color;
  gl::FramebufferName fbo;

  static Expected<ReflectionMap> create(int size);
};

// Filmic's tables on the GPU.
struct FilmicTextures {
  gl::TextureName cube, curve;
  static FilmicTextures upload(const image::FilmicTables& tables);
};

}  // namespace shadelab::scene_render
