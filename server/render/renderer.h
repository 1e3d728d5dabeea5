#pragma once
// Turns a request into frames on one headless context. Owns the context and keeps compiled
// programs and uploaded meshes warm between jobs (a worker process holds one Renderer).
#include <functional>
#include <memory>
#include <vector>

#include "core/expected.h"
#include "egl/headless_context.h"
#include "gl/render_target.h"
#include "image/metrics.h"
#include "render/render_request.h"
#include "scene/mesh.h"

namespace shadelab::render {

struct CompileReport {
  std::vector<std::string> warnings;
  std::vector<Diagnostic> diagnostics;  // warnings from the driver, located in the files
  std::vector<VariableInfo> attributes, uniforms;
  double compile_ms = 0;
  bool cached = false;
};

// The NaN and infinities in the colour a frame's fragments wrote before the canvas stored it in 8
// bits (NaN as 0, infinity clamped), per request and frame: the grader's float check. Counted by
// the draw itself, at every sample the frame holds (docs/grading.md, "The NaN the student saw").
using CensusSink = std::function<void(int request, int frame, const image::NonFinite& counts)>;

class Renderer {
 public:
  static Expected<Renderer> create(const egl::ContextOptions& options);
  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;
  ~Renderer();

  const egl::ContextInfo& context_info() const;

  // How frames are read back (gl::Readback): through pixel buffers on a GPU, directly on llvmpipe,
  // each the faster there. Tests and `shadelab render --readback` choose.
  gl::Readback readback() const;
  void set_readback(gl::Readback mode);

  // What the renderer keeps warm between jobs, for /metrics: at most 32 programs, and 8 meshes'
  // vertex and index buffers within 256 MiB.
  struct CacheSizes {
    std::size_t programs = 0, meshes = 0, mesh_bytes = 0;
  };
  CacheSizes cache_sizes() const;

  // Unwraps, compiles, links and reflects; renders nothing.
  Expected<CompileReport> compile(const shader::ShaderFile& vertex, const shader::ShaderFile& fragment);
  // Renders request.frames frames of `mesh`, handing each to `sink` as soon as it is read back;
  // with a `census`, each frame's count of non-finite colours to it as well.
  Expected<RenderReport> render(const RenderRequest& request, const scene::Mesh& mesh, const FrameSink& sink,
                                const CensusSink& census = {});

  // Requests that differ only in the values of vec3 or vec4 uniforms (the grader's lights), their frames
  // handed to `sink` with the request's index: in one pass over the geometry, the fragment shader
  // run once per request into outputs of its own (shader/uniform_variants.h), where the shaders
  // allow it; else one request after another. The same bytes either way (tests/render_test.cpp).
  // Requests that differ in nothing are rendered once. `report.passes` says how many it took.
  using IndexedSink = std::function<void(int request, int frame, const image::Image& image, bool opaque)>;
  Expected<RenderReport> render_together(const std::vector<RenderRequest>& requests, const scene::Mesh& mesh, const IndexedSink& sink,
                                         const CensusSink& census = {});

 private:
  struct State;
  explicit Renderer(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace shadelab::render
