#include "gl/render_target.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>

namespace shadelab::gl {

namespace {
GLenum internal_format(PixelFormat f) { return f == PixelFormat::rgba8 ? GL_RGBA8 : GL_RGBA32F; }
}  // namespace

RenderbufferName make_renderbuffer(GLenum format, int width, int height, int samples) {
  GLuint id = 0;
  glGenRenderbuffers(1, &id);
  RenderbufferName rb(id);
  glBindRenderbuffer(GL_RENDERBUFFER, id);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width, height);
  return rb;
}

FramebufferName make_framebuffer() {
  GLuint id = 0;
  glGenFramebuffers(1, &id);
  return FramebufferName(id);
}

int max_samples(PixelFormat format) {
  GLint n = 0;
  glGetInternalformativ(GL_RENDERBUFFER, internal_format(format), GL_SAMPLES, 1, &n);
  return n;
}

int max_outputs() {
  GLint n = 0;
  glGetIntegerv(GL_MAX_DRAW_BUFFERS, &n);
  return n;
}

namespace {

GLenum attachment(int k) { return static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + k); }

// Draw buffers 0..outputs-1 to their attachments; with `only`, every slot but that one GL_NONE
// (GLES lets slot k name attachment k or nothing).
void set_draw_buffers(int outputs, int only = -1) {
  std::vector<GLenum> buffers;
  for (int k = 0; k < outputs; ++k) buffers.push_back(only < 0 || only == k ? attachment(k) : GL_NONE);
  glDrawBuffers(static_cast<GLsizei>(buffers.size()), buffers.data());
}

}  // namespace

Expected<RenderTarget> RenderTarget::create(int width, int height, int samples, PixelFormat format, int outputs, int census_outputs) {
  const int max = max_samples(format);
  if (samples < 0 || samples > max)
    return make_error(ErrorCode::msaa_unsupported, "this renderer supports at most " + std::to_string(max) +
                                                       " samples per pixel; " + std::to_string(samples) +
                                                       " were asked for");
  if (outputs < 1 || outputs > max_outputs())
    return make_error(ErrorCode::gl_error, "this renderer draws at most " + std::to_string(max_outputs()) + " outputs at once");
  RenderTarget t;
  t.census_outputs_ = std::clamp(census_outputs, 0, outputs);
  t.width_ = width;
  t.height_ = height;
  t.format_ = format;
  t.draw_fbo_ = make_framebuffer();
  for (int k = 0; k < outputs; ++k) {
    t.color_.push_back(make_renderbuffer(internal_format(format), width, height, samples));
    glBindFramebuffer(GL_FRAMEBUFFER, t.draw_fbo_.get());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, attachment(k), GL_RENDERBUFFER, t.color_.back().get());
  }
  t.depth_ = make_renderbuffer(GL_DEPTH24_STENCIL8, width, height, samples);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, t.depth_.get());
  set_draw_buffers(outputs);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    return make_error(ErrorCode::gl_error, "the driver rejected a " + std::to_string(width) + "x" +
                                               std::to_string(height) + " framebuffer");
  glBindRenderbuffer(GL_RENDERBUFFER, t.color_.front().get());
  glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_SAMPLES, &t.samples_);

  if (samples > 0) {
    t.resolve_fbo_ = make_framebuffer();
    for (int k = 0; k < outputs; ++k) {
      t.resolve_color_.push_back(make_renderbuffer(internal_format(format), width, height, 0));
      glBindFramebuffer(GL_FRAMEBUFFER, t.resolve_fbo_.get());
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, attachment(k), GL_RENDERBUFFER, t.resolve_color_.back().get());
    }
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      return make_error(ErrorCode::gl_error, "the driver rejected the resolve framebuffer");
  }
  return t;
}

size_t RenderTarget::bytes_per_frame() const {
  return static_cast<size_t>(width_) * static_cast<size_t>(height_) * (format_ == PixelFormat::rgba8 ? 4 : 16);
}

void RenderTarget::begin_frame() const {
  glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo_.get());
  set_draw_buffers(outputs());
  glViewport(0, 0, width_, height_);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glClearColor(0.f, 0.f, 0.f, 1.f);
  glClearDepthf(1.f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  constexpr GLfloat zero[4] = {0.f, 0.f, 0.f, 0.f};
  for (int k = outputs() - census_outputs_; k < outputs(); ++k) glClearBufferfv(GL_COLOR, k, zero);
}

void RenderTarget::resolve() const {
  if (!resolve_fbo_) return;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, draw_fbo_.get());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_.get());
  for (int k = 0; k < outputs(); ++k) {  // a blit copies the read buffer to every draw buffer: one at a time
    glReadBuffer(attachment(k));
    set_draw_buffers(outputs(), k);
    glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
}

void RenderTarget::read_pixels(void* dst) const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_ ? resolve_fbo_.get() : draw_fbo_.get());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  for (int k = 0; k < outputs(); ++k) {
    glReadBuffer(attachment(k));
    // `dst` is a pointer or, with a pack buffer bound, an offset into it.
    void* at = reinterpret_cast<void*>(reinterpret_cast<std::uintptr_t>(dst) + static_cast<size_t>(k) * bytes_per_frame());
    glReadPixels(0, 0, width_, height_, GL_RGBA, format_ == PixelFormat::rgba8 ? GL_UNSIGNED_BYTE : GL_FLOAT, at);
  }
}

Fence Fence::after_queued_commands() {
  Fence f;
  f.sync_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  return f;
}

Fence::Fence(Fence&& other) noexcept : sync_(std::exchange(other.sync_, nullptr)) {}

Fence& Fence::operator=(Fence&& other) noexcept {
  if (this != &other) {
    if (sync_) glDeleteSync(sync_);
    sync_ = std::exchange(other.sync_, nullptr);
  }
  return *this;
}

Fence::~Fence() {
  if (sync_) glDeleteSync(sync_);
}

bool Fence::wait() const {
  // The flush with the first wait; then a second at a time for as long as it takes: the job's
  // deadline (the worker is killed past it) bounds a GPU that never gets there.
  GLenum status = glClientWaitSync(sync_, GL_SYNC_FLUSH_COMMANDS_BIT, 0);
  while (status == GL_TIMEOUT_EXPIRED) status = glClientWaitSync(sync_, 0, 1'000'000'000);
  return status == GL_ALREADY_SIGNALED || status == GL_CONDITION_SATISFIED;
}

void RenderTarget::start_read(Readback mode) {
  read_done_ = Fence();  // a read a failed job left behind is not this one
  if (mode == Readback::direct) return;
  if (!pack_buffer_) {
    GLuint id = 0;
    glGenBuffers(1, &id);
    pack_buffer_ = BufferName(id);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, id);
    glBufferData(GL_PIXEL_PACK_BUFFER, static_cast<GLsizeiptr>(bytes_per_read()), nullptr, GL_STREAM_READ);
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, pack_buffer_.get());
  read_pixels(nullptr);  // offset 0 in the bound pack buffer
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  read_done_ = Fence::after_queued_commands();
}

Status RenderTarget::finish_read(void* dst) {
  if (!read_done_) {  // direct
    read_pixels(dst);
    return Ok{};
  }
  const bool passed = read_done_.wait();
  read_done_ = Fence();
  if (!passed) return make_error(ErrorCode::gl_error, "the driver failed while waiting for a frame's readback");
  glBindBuffer(GL_PIXEL_PACK_BUFFER, pack_buffer_.get());
  const auto bytes = static_cast<GLsizeiptr>(bytes_per_read());
  const void* mapped = glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, bytes, GL_MAP_READ_BIT);
  if (mapped) {
    std::memcpy(dst, mapped, static_cast<size_t>(bytes));
    glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  if (!mapped) return make_error(ErrorCode::gl_error, "the driver could not map a frame's pixel buffer");
  return Ok{};
}

}  // namespace shadelab::gl
