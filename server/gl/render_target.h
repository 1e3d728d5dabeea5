#pragma once
// An offscreen target shaped like the browser's WebGL2 drawing buffer: colour + 24-bit depth,
// optionally multisampled and resolved before readback, cleared to opaque black.
#include "core/expected.h"
#include "gl/gl_name.h"

namespace shadelab::gl {

enum class PixelFormat { rgba8, rgba32f };

class RenderTarget {
 public:
  // samples = 0 renders single-sampled. Errors when the driver cannot give the sample count.
  static Expected<RenderTarget> create(int width, int height, int samples, PixelFormat format);

  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }  // what the driver actually allocated
  PixelFormat format() const { return format_; }
  size_t bytes_per_frame() const;

  // Binds the target and sets the homework's frame state: viewport, clear colour (0,0,0,1),
  // clear depth 1, depth test LEQUAL, no blending, no culling; then clears.
  void begin_frame() const;
  // Queues the multisample resolve (no-op when single-sampled). Returns at once: the driver works
  // on it while the caller submits the next frame to another target.
  void resolve() const;
  // Reads the resolved frame into `dst` (bytes_per_frame() bytes), bottom row first; waits only
  // for the commands this target's frame depends on.
  void read(void* dst) const;

 private:
  int width_ = 0, height_ = 0, samples_ = 0;
  PixelFormat format_ = PixelFormat::rgba8;
  FramebufferName draw_fbo_, resolve_fbo_;
  RenderbufferName color_, depth_, resolve_color_;
};

// Storage for one attachment (samples = 0: single-sampled), bound to GL_RENDERBUFFER on return.
RenderbufferName make_renderbuffer(GLenum format, int width, int height, int samples);
FramebufferName make_framebuffer();

// The largest sample count the driver offers for `format`.
int max_samples(PixelFormat format);

}  // namespace shadelab::gl
