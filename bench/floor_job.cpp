#include "floor_job.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#include <png.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "canonical_job.h"
#include "fresh_shader.h"
#include "render/homework_contract.h"
#include "scene/mesh.h"
#include "shader/shader_source.h"

namespace shadelab::bench {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "floor job: %s\n", what.c_str());
  std::exit(1);
}

void open_context() {
  auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  EGLDisplay display = get_display ? get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr) : EGL_NO_DISPLAY;
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) fail("no EGL display");
  eglBindAPI(EGL_OPENGL_ES_API);
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
  EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) fail("no GLES 3 context");
  std::fprintf(stderr, "renderer: %s\n", reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
}

GLuint compile(GLenum type, const std::string& source) {
  GLuint s = glCreateShader(type);
  const char* text = source.c_str();
  glShaderSource(s, 1, &text, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) fail("a preset shader does not compile");
  return s;
}

GLuint link(const std::string& vertex, const std::string& fragment) {
  GLuint p = glCreateProgram();
  GLuint vs = compile(GL_VERTEX_SHADER, vertex), fs = compile(GL_FRAGMENT_SHADER, fragment);
  glAttachShader(p, vs);
  glAttachShader(p, fs);
  glBindAttribLocation(p, 0, render::kPositionAttribute);
  glBindAttribLocation(p, 1, render::kNormalAttribute);
  glLinkProgram(p);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) fail("the preset does not link");
  glDeleteShader(vs);
  glDeleteShader(fs);
  return p;
}

struct Framebuffers {
  GLuint multisampled = 0, resolved = 0;
};

Framebuffers make_framebuffers(const render::RenderRequest& r) {
  Framebuffers f;
  GLuint colour = 0, depth = 0, resolved_colour = 0;
  glGenRenderbuffers(1, &colour);
  glBindRenderbuffer(GL_RENDERBUFFER, colour);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, r.msaa, GL_RGBA8, r.width, r.height);
  glGenRenderbuffers(1, &depth);
  glBindRenderbuffer(GL_RENDERBUFFER, depth);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, r.msaa, GL_DEPTH_COMPONENT24, r.width, r.height);
  glGenFramebuffers(1, &f.multisampled);
  glBindFramebuffer(GL_FRAMEBUFFER, f.multisampled);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  glGenRenderbuffers(1, &resolved_colour);
  glBindRenderbuffer(GL_RENDERBUFFER, resolved_colour);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, r.width, r.height);
  glGenFramebuffers(1, &f.resolved);
  glBindFramebuffer(GL_FRAMEBUFFER, f.resolved);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolved_colour);
  return f;
}

GLuint upload(const scene::Mesh& mesh) {
  const std::vector<float> corners = mesh.interleaved();
  GLuint vao = 0, vbo = 0;
  glGenVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glGenBuffers(1, &vbo);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(corners.size() * sizeof(float)), corners.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
  return vao;
}

void png_append(png_structp png, png_bytep data, png_size_t size) {
  auto* out = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + size);
}

// The grid as RGB rows, top row first, into a PNG in memory.
std::vector<unsigned char> encode_png(const std::vector<unsigned char>& rgb, int width, int height) {
  std::vector<unsigned char> out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) fail("libpng failed");
  png_set_write_fn(png, &out, png_append, nullptr);
  png_set_compression_level(png, 1);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y) png_write_row(png, const_cast<unsigned char*>(&rgb[static_cast<size_t>(y) * static_cast<size_t>(width) * 3]));
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return out;
}

// The course's job (`r`: its size, frames, samples, camera and uniform values) with these shaders.
FloorPhases one_job(const render::RenderRequest& r, const std::string& vertex, const std::string& fragment, GLuint vao, GLsizei corners,
                    const Framebuffers& fb) {
  const int width = r.width, height = r.height, frames_count = r.frames, columns = 3;
  FloorPhases p;
  const auto start = Clock::now();
  GLuint program = link(vertex, fragment);
  glUseProgram(program);
  for (const auto& u : r.page.uniforms) {
    const GLint at = glGetUniformLocation(program, u.name.c_str());
    if (at >= 0 && u.components == 4) glUniform4fv(at, 1, u.value.data());
    if (at >= 0 && u.components == 3) glUniform3fv(at, 1, u.value.data());
  }
  p.compile = ms_since(start);

  std::vector<unsigned char> frames(static_cast<size_t>(frames_count) * width * height * 4);
  glViewport(0, 0, width, height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  for (int k = 0; k < frames_count; ++k) {
    const auto frame_start = Clock::now();
    const auto t = render::homework_transforms(r.page.camera, width, height, render::frame_angle(r, k));
    glUniformMatrix4fv(glGetUniformLocation(program, render::kWorldToClip), 1, GL_FALSE, glm::value_ptr(t.world_to_clip));
    glUniformMatrix4fv(glGetUniformLocation(program, render::kMeshToWorld), 1, GL_FALSE, glm::value_ptr(t.mesh_to_world));
    glUniformMatrix4fv(glGetUniformLocation(program, render::kMeshToWorldRot), 1, GL_FALSE, glm::value_ptr(t.mesh_to_world_rot));
    glBindFramebuffer(GL_FRAMEBUFFER, fb.multisampled);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, corners);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fb.multisampled);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fb.resolved);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glFinish();
    p.render += ms_since(frame_start);
    const auto read_start = Clock::now();
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fb.resolved);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, &frames[static_cast<size_t>(k) * width * height * 4]);
    p.readback += ms_since(read_start);
  }
  glDeleteProgram(program);

  const auto encode_start = Clock::now();
  const int rows = (frames_count + columns - 1) / columns;
  const int grid_width = columns * width, grid_height = rows * height;
  std::vector<unsigned char> rgb(static_cast<size_t>(grid_width) * grid_height * 3);
  for (int k = 0; k < frames_count; ++k)
    for (int y = 0; y < height; ++y) {
      // glReadPixels gives the bottom row first; a PNG starts at the top.
      const unsigned char* from = &frames[(static_cast<size_t>(k) * height + static_cast<size_t>(height - 1 - y)) * width * 4];
      unsigned char* to = &rgb[((static_cast<size_t>(k / columns) * height + static_cast<size_t>(y)) * grid_width + static_cast<size_t>(k % columns) * width) * 3];
      for (int x = 0; x < width; ++x) std::memcpy(to + x * 3, from + x * 4, 3);
    }
  const auto png = encode_png(rgb, grid_width, grid_height);
  p.encode = ms_since(encode_start);
  p.total = ms_since(start);
  if (png.size() < 1000) fail("the grid PNG is empty");
  return p;
}

std::string glsl_of(const shader::ShaderFile& file, shader::Stage stage) {
  auto unwrapped = shader::unwrap(file, stage);
  if (!unwrapped) fail("the preset does not unwrap");
  return unwrapped->glsl;
}

}  // namespace

struct FloorJob::State {
  render::RenderRequest request = canonical_request();
  std::string vertex, fragment;
  GLuint vao = 0;
  GLsizei corners = 0;
  Framebuffers framebuffers;
};

FloorJob::FloorJob() : state_(std::make_unique<State>()) {
  const scene::Mesh& mesh = canonical_mesh();
  state_->vertex = glsl_of(state_->request.vertex, shader::Stage::vertex);
  state_->fragment = glsl_of(state_->request.fragment, shader::Stage::fragment);
  open_context();
  state_->vao = upload(mesh);
  state_->corners = static_cast<GLsizei>(mesh.positions.size());
  state_->framebuffers = make_framebuffers(state_->request);
}

FloorJob::~FloorJob() = default;

FloorPhases FloorJob::run(unsigned serial) {
  return one_job(state_->request, state_->vertex, with_fresh_branch(state_->fragment, serial), state_->vao, state_->corners,
                 state_->framebuffers);
}

}  // namespace shadelab::bench
