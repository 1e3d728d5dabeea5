#pragma once
// An offscreen target shaped like the browser's WebGL2 drawing buffer: colour + 24-bit depth,
// optionally multisampled and resolved before readback, cleared to opaque black.
#include <vector>

#include "core/expected.h"
#include "gl/gl_name.h"

namespace shadelab::gl {

enum class PixelFormat { rgba8, rgba32f };

// How a frame leaves the driver.
// - direct: glReadPixels into memory, which waits for the frame and copies it. On llvmpipe the
//   "GPU" is this process's own threads, and this is the fastest (docs/performance-log.md).
// - pixel_buffer: glReadPixels into a pixel pack buffer, with a fence behind it. A GPU copies the
//   frame out while it renders the next one; the CPU maps the buffer once the fence has passed.
enum class Readback { direct, pixel_buffer };

// A fence in the command stream (glFenceSync), move-only; deleted with its owner.
class Fence {
 public:
  Fence() = default;
  static Fence after_queued_commands();
  Fence(Fence&& other) noexcept;
  Fence& operator=(Fence&& other) noexcept;
  Fence(const Fence&) = delete;
  Fence& operator=(const Fence&) = delete;
  ~Fence();
  explicit operator bool() const { return sync_ != nullptr; }
  // Flushes and blocks until the GPU has passed the fence; false if the driver says it failed.
  bool wait() const;

 private:
  GLsync sync_ = nullptr;
};

class RenderTarget {
 public:
  // samples = 0 renders single-sampled. `outputs` colour attachments of one format, drawn together
  // (location k to attachment k); the last `census_outputs` of them start each frame at zero, not at
  // the canvas's opaque black (the grader's flags, shader/uniform_variants.h). Errors when the
  // driver cannot give the sample count or the outputs.
  static Expected<RenderTarget> create(int width, int height, int samples, PixelFormat format, int outputs = 1, int census_outputs = 0);

  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }  // what the driver actually allocated
  PixelFormat format() const { return format_; }
  int outputs() const { return static_cast<int>(color_.size()); }
  int census_outputs() const { return census_outputs_; }
  size_t bytes_per_frame() const;                                     // one output's
  size_t bytes_per_read() const { return bytes_per_frame() * color_.size(); }  // every output's

  // Binds the target and sets the homework's frame state: viewport, clear colour (0,0,0,1),
  // clear depth 1, depth test LEQUAL, no blending, no culling; then clears (census outputs to 0).
  void begin_frame() const;
  // Queues the multisample resolve (no-op when single-sampled). Returns at once: the driver works
  // on it while the caller submits the next frame to another target.
  void resolve() const;
  // Starts taking the resolved frame out. With Readback::pixel_buffer the copy is queued behind
  // the frame and this returns at once; with direct, nothing happens until finish_read.
  void start_read(Readback mode);
  // Copies the frame that start_read began into `dst` (bytes_per_read() bytes: output 0's frame,
  // then output 1's, ...), bottom row first; waits only for the commands this target's frame depends on.
  Status finish_read(void* dst);

 private:
  // glReadPixels of each resolved output into `dst`, one after another: memory, or offsets into a
  // bound pack buffer.
  void read_pixels(void* dst) const;

  int width_ = 0, height_ = 0, samples_ = 0, census_outputs_ = 0;
  PixelFormat format_ = PixelFormat::rgba8;
  FramebufferName draw_fbo_, resolve_fbo_;
  std::vector<RenderbufferName> color_, resolve_color_;  // one per output
  RenderbufferName depth_;
  BufferName pack_buffer_;  // made on the first pixel_buffer read
  Fence read_done_;         // set while a pixel_buffer read is in flight
};

// Storage for one attachment (samples = 0: single-sampled), bound to GL_RENDERBUFFER on return.
RenderbufferName make_renderbuffer(GLenum format, int width, int height, int samples);
FramebufferName make_framebuffer();

// The largest sample count the driver offers for `format`.
int max_samples(PixelFormat format);
// How many outputs one draw can write (GL_MAX_DRAW_BUFFERS; at least 4 in GLES 3).
int max_outputs();

}  // namespace shadelab::gl
