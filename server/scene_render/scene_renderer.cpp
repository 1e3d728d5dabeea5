#include "scene_render/scene_renderer.h"

#include <EGL/egl.h>

#include <cstring>

#include "image/view_transform.h"
#include "scene/scene_mesh.h"
#include "scene_render/scene_passes.h"

namespace shadelab::scene_render {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// Meshes kept warm between renders. A render pins the meshes it draws, so it may hold more.
constexpr size_t kMeshCacheEntries = 32;

// Sets the clip-space depth range for one render and restores GL's default afterwards, so the
// homework renderer sharing the context is unaffected.
class ClipControlScope {
 public:
  explicit ClipControlScope(const RenderState& s) : s_(s) {
    if (s_.clip_control) s_.clip_control(GL_LOWER_LEFT_EXT, GL_ZERO_TO_ONE_EXT);
  }
  ~ClipControlScope() {
    if (s_.clip_control) s_.clip_control(GL_LOWER_LEFT_EXT, GL_NEGATIVE_ONE_TO_ONE_EXT);
  }
  ClipControlScope(const ClipControlScope&) = delete;
  ClipControlScope& operator=(const ClipControlScope&) = delete;

 private:
  const RenderState& s_;
};

// Times each pass: llvmpipe renders lazily, so glFinish makes each pass's time its own.
class PassClock {
 public:
  explicit PassClock(SceneReport& report) : report_(report) {}
  void finish(PassDetail detail, bool wait_for_gpu = true) {
    if (wait_for_gpu) glFinish();
    report_.passes.push_back({ms_since(lap_), std::move(detail)});
    lap_ = Clock::now();
  }

 private:
  SceneReport& report_;
  Clock::time_point lap_ = Clock::now();
};

}  // namespace

Expected<scene::Mesh> resolve_builtin_mesh(const std::string& reference) { return scene::builtin_scene_mesh(reference); }

Expected<std::shared_ptr<const GpuMesh>> RenderState::mesh(const std::string& reference, scene::Shading shading,
                                                           const MeshResolver& resolve) {
  const std::string key = reference + (shading == scene::Shading::flat ? "|flat" : "|smooth");
  if (auto it = meshes.find(key); it != meshes.end()) return it->second;
  auto loaded = resolve(reference);
  if (!loaded) return loaded.take_error();
  scene::apply_shading(*loaded, shading);
  auto g = std::make_shared<GpuMesh>();
  g->buffer = gl::MeshBuffer::upload(loaded->interleaved());
  for (const auto& p : loaded->positions) g->bounds.add(glm::dvec3(p));
  g->mesh = std::move(*loaded);
  // Evicting only drops the cache's reference: a render that draws the mesh still holds one.
  if (meshes.size() >= kMeshCacheEntries) meshes.erase(meshes.begin());
  return meshes.emplace(key, std::move(g)).first->second;
}

Status RenderState::ensure_filmic() {
  if (filmic) return Ok{};
  if (!filmic_error.empty()) return make_error(ErrorCode::view_transform_unavailable, filmic_error);
  auto tables = image::bake_filmic(image::blender_ocio_config_path());
  if (!tables) {
    filmic_error = tables.error().message;
    return tables.take_error();
  }
  filmic = FilmicTextures::upload(*tables);
  return Ok{};
}

SceneRenderer::SceneRenderer(std::unique_ptr<RenderState> state) : state_(std::move(state)) {}
SceneRenderer::SceneRenderer(SceneRenderer&&) noexcept = default;
SceneRenderer& SceneRenderer::operator=(SceneRenderer&&) noexcept = default;
SceneRenderer::~SceneRenderer() = default;

Expected<SceneRenderer> SceneRenderer::create() {
  auto state = std::make_unique<RenderState>();
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i)
    if (std::strcmp(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i))), "GL_EXT_clip_control") == 0)
      state->clip_control = reinterpret_cast<PFNGLCLIPCONTROLEXTPROC>(eglGetProcAddress("glClipControlEXT"));
  state->convention = {.zero_to_one = state->clip_control != nullptr, .reversed = state->clip_control != nullptr};
  GLuint vao = 0;
  glGenVertexArrays(1, &vao);
  state->empty_vao = gl::VertexArrayName(vao);
  return SceneRenderer(std::move(state));
}

Expected<SceneRender> SceneRenderer::render(const scene::SceneDescription& scene, const MeshResolver& resolve,
                                            const SceneRenderOptions& options) {
  RenderState& st = *state_;
  const auto start = Clock::now();
  SceneRender out;
  SceneReport& report = out.report;
  report.engine = scene.render.engine;
  report.view_transform = scene.render.view_transform;
  report.width = scene.render.width;
  report.height = scene.render.height;
  report.depth = st.convention.reversed ? "reversed-z float32" : "forward float32";
  PassClock clock(report);
  ClipControlScope clip_scope(st);

  auto frame = setup_pass(st, scene, resolve);
  if (!frame) return frame.take_error();
  Frame& f = *frame;
  report.features = f.plan.features();
  out.camera = f.camera;
  report.camera = {f.camera.horizontal_fov_degrees(), f.camera.vertical_fov_degrees(), f.camera.type};
  clock.finish(SetupDetail{static_cast<int>(f.opaque.size() + f.transparent.size())}, false);

  if (f.plan.shadows) {
    auto shadow = shadow_pass(st, f);
    if (!shadow) return shadow.take_error();
    if (shadow->views > 0) clock.finish(*shadow);
  }
  if (f.plan.reflection && f.ground) {
    auto reflection = reflection_pass(st, f);
    if (!reflection) return reflection.take_error();
    clock.finish(*reflection);
  }
  auto main = main_pass(st, f);
  if (!main) return main.take_error();
  clock.finish(*main);
  auto view = view_pass(st, f);
  if (!view) return view.take_error();
  clock.finish(*view);
  readback_pass(st, f, options.keep_radiance, out);
  clock.finish(ReadbackDetail{}, false);
  if (f.plan.framing) {
    auto framing = framing_pass(st, f, report.framing);
    if (!framing) return framing.take_error();
    clock.finish(*framing);
  }

  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  report.total_ms = ms_since(start);
  return out;
}

}  // namespace shadelab::scene_render
