#include "scene_render/scene_renderer.h"

#include <EGL/egl.h>
#include <GLES3/gl32.h>
#include <GLES2/gl2ext.h>  // after gl32.h, which defines what it needs

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "gl/mesh_buffer.h"
#include "image/view_transform.h"
#include "scene/pass_plan.h"
#include "scene/scene_mesh.h"
#include "scene_render/depth_convention.h"
#include "scene_render/gpu_resources.h"
#include "scene_render/scene_program.h"
#include "scene_render/shadow_views.h"

namespace shadelab::scene_render {

namespace {

using Clock = std::chrono::steady_clock;
using scene::SceneDescription;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

struct GpuMesh {
  scene::Mesh mesh;
  gl::MeshBuffer buffer;
  Aabb bounds;  // object space
};

// One object as the passes draw it: which mesh, where, with what material.
struct DrawItem {
  int object = -1;  // index into scene.objects; -1 for the ground
  const GpuMesh* mesh = nullptr;
  glm::dmat4 world_from_object{1.0};
  const scene::Material* material = nullptr;
};

// The uniforms every lit draw of one pass shares, computed in double for that pass's camera.
struct FrameUniforms {
  glm::dmat4 camera_from_world{1.0};
  glm::dmat4 projection{1.0};
  bool orthographic = false;
  int light_count = 0;
  std::array<int, kMaxLights> light_type{};
  std::array<glm::vec3, kMaxLights> light_value{}, light_position{}, light_direction{};
  std::array<glm::vec4, kMaxLights> light_shape{};
  int shadow_views = 0;
  std::array<glm::mat4, kMaxShadowViews> shadow_matrix{};
  std::array<glm::vec4, kMaxShadowViews> shadow_a{}, shadow_b{};
  glm::vec3 world{0.f}, ground_bounce{0.f}, world_up{0.f}, camera_from_ground{0.f}, workbench_direction{0.f};
  glm::mat3 world_from_camera{1.f};
};

template <class T>
void set(const SceneProgram& p, const char* name, const T& value) {
  const GLint l = p.uniform(name);
  if (l < 0) return;
  if constexpr (std::is_same_v<T, float>) glUniform1f(l, value);
  else if constexpr (std::is_same_v<T, int>) glUniform1i(l, value);
  else if constexpr (std::is_same_v<T, bool>) glUniform1i(l, value ? 1 : 0);
  else if constexpr (std::is_same_v<T, glm::vec2>) glUniform2fv(l, 1, glm::value_ptr(value));
  else if constexpr (std::is_same_v<T, glm::vec3>) glUniform3fv(l, 1, glm::value_ptr(value));
  else if constexpr (std::is_same_v<T, glm::mat3>) glUniformMatrix3fv(l, 1, GL_FALSE, glm::value_ptr(value));
  else if constexpr (std::is_same_v<T, glm::mat4>) glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(value));
  else static_assert(sizeof(T) == 0, "unsupported uniform type");
}

glm::vec3 f3(const glm::dvec3& v) { return glm::vec3(v); }

// Irradiance a light gives a surface at `p` facing `normal` (no shadow, spot cone ignored).
double irradiance(const scene::Light& l, const glm::dvec3& p, const glm::dvec3& normal) {
  const double colour = (l.color.r + l.color.g + l.color.b) / 3;
  if (l.type == scene::LightType::sun) return colour * l.strength * std::max(0.0, -glm::dot(light_direction(l), normal));
  const glm::dvec3 d = l.location - p;
  const double dist2 = std::max(glm::dot(d, d), std::max(l.radius * l.radius, 1e-8));
  const double intensity = l.type == scene::LightType::area ? l.power_w / std::numbers::pi : l.power_w / (4 * std::numbers::pi);
  return colour * intensity * std::max(0.0, glm::dot(glm::normalize(d), normal)) / dist2;
}

class DepthState {
 public:
  explicit DepthState(const DepthConvention& c) : c_(c) {}
  void camera_pass() const {
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDepthFunc(c_.reversed ? GL_GREATER : GL_LESS);
    glClearDepthf(c_.reversed ? 0.f : 1.f);
  }
  void forward_pass() const {
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glClearDepthf(1.f);
  }

 private:
  DepthConvention c_;
};

}  // namespace

Expected<scene::Mesh> resolve_builtin_mesh(const std::string& reference) { return scene::builtin_scene_mesh(reference); }

struct SceneRenderer::State {
  DepthConvention convention;
  PFNGLCLIPCONTROLEXTPROC clip_control = nullptr;
  ProgramCache programs;
  std::map<std::string, GpuMesh> meshes;  // reference + shading
  std::optional<FrameTargets> frame;
  std::optional<IdTarget> ids, guard;
  std::optional<ShadowArray> shadows;
  std::optional<ReflectionMap> reflection;
  std::optional<FilmicTextures> filmic;
  std::string filmic_error;
  gl::VertexArrayName empty_vao;

  // Sets the clip-space depth range for this render and restores GL's default afterwards, so the
  // homework renderer sharing the context is unaffected.
  struct ClipControlScope {
    const State& s;
    explicit ClipControlScope(const State& state) : s(state) {
      if (s.clip_control) s.clip_control(GL_LOWER_LEFT_EXT, GL_ZERO_TO_ONE_EXT);
    }
    ~ClipControlScope() {
      if (s.clip_control) s.clip_control(GL_LOWER_LEFT_EXT, GL_NEGATIVE_ONE_TO_ONE_EXT);
    }
  };

  Expected<const GpuMesh*> mesh(const std::string& reference, scene::Shading shading, const MeshResolver& resolve) {
    const std::string key = reference + (shading == scene::Shading::flat ? "|flat" : "|smooth");
    if (auto it = meshes.find(key); it != meshes.end()) return &it->second;
    auto loaded = resolve(reference);
    if (!loaded) return loaded.take_error();
    scene::apply_shading(*loaded, shading);
    GpuMesh g;
    g.buffer = gl::MeshBuffer::upload(loaded->interleaved());
    for (const auto& p : loaded->positions) g.bounds.add(glm::dvec3(p));
    g.mesh = std::move(*loaded);
    if (meshes.size() >= 32) meshes.erase(meshes.begin());
    return &meshes.emplace(key, std::move(g)).first->second;
  }

  Status ensure_filmic() {
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
};

SceneRenderer::SceneRenderer(std::unique_ptr<State> state) : state_(std::move(state)) {}
SceneRenderer::SceneRenderer(SceneRenderer&&) noexcept = default;
SceneRenderer& SceneRenderer::operator=(SceneRenderer&&) noexcept = default;
SceneRenderer::~SceneRenderer() = default;

Expected<SceneRenderer> SceneRenderer::create() {
  auto state = std::make_unique<State>();
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

namespace {

// Everything one render needs, so the passes below read as a list.
struct Frame {
  const SceneDescription& scene;
  scene::PassPlan plan;
  scene::CameraModel camera;
  std::vector<DrawItem> opaque, transparent;
  std::optional<DrawItem> ground;
  std::vector<ShadowView> views;
  std::vector<int> first_view;  // per light: its first shadow view, or -1
  Aabb bounds;                  // everything drawn, world space
  glm::dvec3 workbench_light{0.0};  // the way Workbench's shadow light travels (world)
};

void draw(const DrawItem& item, const SceneProgram& program, const FrameUniforms& u, bool lit) {
  const glm::dmat4 model_view = u.camera_from_world * item.world_from_object;
  if (lit) {
    const glm::dmat3 linear(model_view);
    set(program, "uModelView", glm::mat4(model_view));
    set(program, "uNormalMatrix", glm::mat3(glm::transpose(glm::inverse(linear))));
    set(program, "uFlipFacing", glm::determinant(linear) < 0);
    const scene::Material& m = *item.material;
    set(program, "uBaseColor", f3(m.base_color));
    set(program, "uMetallic", static_cast<float>(m.metallic));
    set(program, "uRoughness", static_cast<float>(m.roughness));
    set(program, "uSpecular", static_cast<float>(m.specular));
    set(program, "uAlpha", static_cast<float>(m.alpha));
    set(program, "uSubsurface", static_cast<float>(m.subsurface));
    set(program, "uSubsurfaceColor", f3(m.subsurface_color));
    // How far past the terminator light reaches, per channel: more for a longer scattering radius.
    set(program, "uSubsurfaceWrap", f3(m.subsurface * m.subsurface_radius / (m.subsurface_radius + 0.5)));
    set(program, "uEmission", f3(m.emission * m.emission_strength));
  } else {
    set(program, "uModelViewProjection", glm::mat4(u.projection * model_view));
  }
  item.mesh->buffer.draw(0, lit ? 1 : -1);
}

FrameUniforms frame_uniforms(const Frame& f, const glm::dmat4& camera_from_world, const glm::dmat4& projection,
                             bool orthographic, const DepthConvention& convention, int shadow_size) {
  FrameUniforms u;
  u.camera_from_world = camera_from_world;
  u.projection = projection;
  u.orthographic = orthographic;
  const glm::dmat4 world_from_camera = glm::inverse(camera_from_world);
  const glm::dmat3 rotation(camera_from_world);
  u.world_from_camera = glm::mat3(glm::dmat3(world_from_camera));
  u.world_up = f3(glm::normalize(rotation * glm::dvec3(0, 0, 1)));
  const SceneDescription& s = f.scene;
  u.world = f3(s.world.color * s.world.strength);

  // The ground as the objects' lower hemisphere sees it: lit by every light and the world at the
  // point under the objects (no shadows). Without a ground the world surrounds everything.
  glm::dvec3 bounce = s.world.color * s.world.strength;
  if (s.ground) {
    glm::dvec3 centre(0, 0, s.ground->height);
    if (!f.bounds.empty()) centre = glm::dvec3(0.5 * (f.bounds.min.x + f.bounds.max.x), 0.5 * (f.bounds.min.y + f.bounds.max.y), s.ground->height);
    double e = 0;
    for (const auto& l : s.lights) e += irradiance(l, centre, {0, 0, 1});
    const scene::Material& g = s.ground->material;
    bounce = g.base_color * (1 - g.metallic) * (e / std::numbers::pi) + g.base_color * (1 - g.metallic) * bounce;
    u.camera_from_ground = f3(glm::dvec3(world_from_camera[3]) - glm::dvec3(0, 0, s.ground->height));
  }
  u.ground_bounce = f3(bounce);

  u.light_count = static_cast<int>(std::min<size_t>(s.lights.size(), kMaxLights));
  for (int i = 0; i < u.light_count; ++i) {
    const scene::Light& l = s.lights[static_cast<size_t>(i)];
    const glm::dvec3 dir = light_direction(l);
    u.light_direction[i] = f3(glm::normalize(rotation * dir));
    u.light_position[i] = f3(glm::dvec3(camera_from_world * glm::dvec4(l.location, 1.0)));
    double shape_x = l.radius, cos_outer = -2, blend = 1;
    double value = l.power_w / (4 * std::numbers::pi);  // point, spot: W -> W/sr
    switch (l.type) {
      case scene::LightType::sun:
        u.light_type[i] = 1;
        value = l.strength;
        shape_x = std::tan(l.angle_degrees * std::numbers::pi / 360);
        break;
      case scene::LightType::spot: {
        u.light_type[i] = 2;
        cos_outer = std::cos(l.spot_size_degrees * std::numbers::pi / 360);
        blend = (1 - cos_outer) * l.spot_blend;  // Blender's spot blend, as a cosine width
        break;
      }
      case scene::LightType::area:
        u.light_type[i] = 3;
        value = l.power_w / std::numbers::pi;  // a Lambertian emitter: intensity along its normal
        shape_x = 0.5 * l.size;
        break;
      case scene::LightType::point: u.light_type[i] = 0; break;
    }
    u.light_value[i] = f3(l.color * value);
    u.light_shape[i] = glm::vec4(shape_x, cos_outer, blend, static_cast<float>(f.first_view[static_cast<size_t>(i)]));
  }

  u.shadow_views = static_cast<int>(std::min<size_t>(f.views.size(), kMaxShadowViews));
  const glm::dmat4 to_texture = clip_to_texture(convention);
  for (int k = 0; k < u.shadow_views; ++k) {
    const ShadowView& v = f.views[static_cast<size_t>(k)];
    u.shadow_matrix[k] = glm::mat4(to_texture * v.clip_from_light * (v.light_from_world * world_from_camera));
    u.shadow_a[k] = glm::vec4(v.perspective ? 1.f : 0.f, v.near, v.far, v.light_size);
    u.shadow_b[k] = glm::vec4(v.half_extent, 2 * v.half_extent / shadow_size, 1.0 / shadow_size, 0);
  }
  u.workbench_direction = f3(-glm::normalize(rotation * f.workbench_light));
  return u;
}

void upload(const SceneProgram& p, const FrameUniforms& u) {
  set(p, "uProjection", glm::mat4(u.projection));
  set(p, "uOrthographic", u.orthographic);
  set(p, "uWorldUp", u.world_up);
  set(p, "uWorldFromCamera", u.world_from_camera);
  set(p, "uWorld", u.world);
  set(p, "uGroundBounce", u.ground_bounce);
  set(p, "uCameraFromGround", u.camera_from_ground);
  set(p, "uWorkbenchShadowDirection", u.workbench_direction);
  set(p, "uLightCount", u.light_count);
  if (u.light_count > 0) {
    const auto n = u.light_count;
    if (GLint l = p.uniform("uLightType[0]"); l >= 0) glUniform1iv(l, n, u.light_type.data());
    if (GLint l = p.uniform("uLightValue[0]"); l >= 0) glUniform3fv(l, n, glm::value_ptr(u.light_value[0]));
    if (GLint l = p.uniform("uLightPosition[0]"); l >= 0) glUniform3fv(l, n, glm::value_ptr(u.light_position[0]));
    if (GLint l = p.uniform("uLightDirection[0]"); l >= 0) glUniform3fv(l, n, glm::value_ptr(u.light_direction[0]));
    if (GLint l = p.uniform("uLightShape[0]"); l >= 0) glUniform4fv(l, n, glm::value_ptr(u.light_shape[0]));
  }
  if (u.shadow_views > 0) {
    const auto n = u.shadow_views;
    if (GLint l = p.uniform("uShadowMatrix[0]"); l >= 0) glUniformMatrix4fv(l, n, GL_FALSE, glm::value_ptr(u.shadow_matrix[0]));
    if (GLint l = p.uniform("uShadowA[0]"); l >= 0) glUniform4fv(l, n, glm::value_ptr(u.shadow_a[0]));
    if (GLint l = p.uniform("uShadowB[0]"); l >= 0) glUniform4fv(l, n, glm::value_ptr(u.shadow_b[0]));
  }
  set(p, "uShadowDepth", 1);
  set(p, "uShadowRaw", 2);
  set(p, "uReflection", 3);
}

ShaderVariant lit_variant(const SceneDescription& s, const scene::PassPlan& plan, bool radiance_only) {
  ShaderVariant v;
  v.defines["MAX_LIGHTS"] = std::to_string(kMaxLights);
  v.defines["MAX_SHADOW_VIEWS"] = std::to_string(kMaxShadowViews);
  if (s.render.engine == scene::Engine::workbench) {
    v.defines["ENGINE_WORKBENCH"] = "1";
  } else {
    v.defines["ENGINE_EEVEE"] = "1";
    if (plan.subsurface) v.defines["HAS_SUBSURFACE"] = "1";
    if (plan.emission) v.defines["HAS_EMISSION"] = "1";
    if (plan.reflection && !radiance_only) v.defines["HAS_REFLECTION"] = "1";
    if (radiance_only) v.defines["RADIANCE_ONLY"] = "1";
  }
  if (plan.shadows) {
    v.defines["HAS_SHADOWS"] = "1";
    v.defines["SHADOW_TAPS"] = std::to_string(s.render.shadow_filter_taps);
  }
  return v;
}

}  // namespace

Expected<SceneRender> SceneRenderer::render(const SceneDescription& scene, const MeshResolver& resolve,
                                           const SceneRenderOptions& options) {
  State& st = *state_;
  const auto start = Clock::now();
  auto lap = start;
  SceneReport report;
  const auto finish_pass = [&](std::string name, nlohmann::json detail) {
    glFinish();  // llvmpipe renders lazily; finishing here makes each pass's time its own
    report.passes.push_back({std::move(name), ms_since(lap), std::move(detail)});
    lap = Clock::now();
  };
  State::ClipControlScope clip_scope(st);
  report.depth = st.convention.reversed ? "reversed-z float32" : "forward float32";

  Frame f{scene, scene::plan_passes(scene), scene::make_camera(scene.camera, scene.render.width, scene.render.height),
          {}, {}, {}, {}, {}, {}};
  report.features = f.plan.features();
  report.camera = f.camera;
  const int width = scene.render.width, height = scene.render.height;

  // Meshes and placements.
  for (int index : f.plan.drawn_objects) {
    const scene::Object& o = scene.objects[static_cast<size_t>(index)];
    auto m = st.mesh(o.mesh, o.shading, resolve);
    if (!m) {
      Error e = m.take_error();
      e.message = "objects[" + std::to_string(index) + "] ('" + o.name + "'): " + e.message;
      return e;
    }
    DrawItem item{index, *m, scene::object_matrix(o.location, scene::euler_xyz_degrees(o.rotation_degrees), o.scale), &o.material};
    for (int c = 0; c < 8; ++c) {
      const Aabb& b = item.mesh->bounds;
      const glm::dvec3 corner{c & 1 ? b.max.x : b.min.x, c & 2 ? b.max.y : b.min.y, c & 4 ? b.max.z : b.min.z};
      f.bounds.add(glm::dvec3(item.world_from_object * glm::dvec4(corner, 1)));
    }
    (o.material.alpha < 1 && scene.render.engine == scene::Engine::eevee ? f.transparent : f.opaque).push_back(item);
  }
  if (scene.ground) {
    auto plane = st.mesh("plane", scene::Shading::flat, resolve_builtin_mesh);
    if (!plane) return plane.take_error();
    const double half = scene.ground->size / 2;
    f.ground = DrawItem{-1, *plane, scene::object_matrix({0, 0, scene.ground->height}, glm::dmat3(1.0), {half, half, 1}),
                        &scene.ground->material};
    f.bounds.add({-half, -half, scene.ground->height});
    f.bounds.add({half, half, scene.ground->height});
  }
  std::vector<DrawItem> everything = f.opaque;
  everything.insert(everything.end(), f.transparent.begin(), f.transparent.end());
  if (f.ground) everything.push_back(*f.ground);

  // Shadow views: Eevee's shadow-casting lights; Workbench's one shadow light (the first sun, else
  // Blender's default Workbench light direction).
  SceneDescription shadow_scene_storage;
  const SceneDescription* shadow_scene = &scene;
  std::vector<int> shadow_lights = f.plan.shadow_lights;
  if (scene.render.engine == scene::Engine::workbench && f.plan.shadows) {
    shadow_scene_storage.lights = {};
    scene::Light sun;
    sun.type = scene::LightType::sun;
    sun.target = glm::dvec3(-0.57735, -0.57735, -0.57735);
    sun.location = glm::dvec3(0.0);
    for (const auto& l : scene.lights)
      if (l.type == scene::LightType::sun) {
        sun = l;
        break;
      }
    shadow_scene_storage.lights.push_back(sun);
    shadow_scene = &shadow_scene_storage;
    shadow_lights = {0};
    f.workbench_light = light_direction(sun);
  }
  f.first_view.assign(scene.lights.size(), -1);
  if (f.plan.shadows) {
    // A light whose views do not all fit in the shader's array casts no shadow (a point light
    // needs six): reported in the shadow pass's detail.
    std::vector<ShadowView> views = shadow_views(*shadow_scene, shadow_lights, f.bounds, st.convention);
    for (size_t k = 0; k < views.size();) {
      size_t n = 1;
      while (k + n < views.size() && views[k + n].light == views[k].light) ++n;
      if (f.views.size() + n <= static_cast<size_t>(kMaxShadowViews))
        f.views.insert(f.views.end(), views.begin() + static_cast<long>(k), views.begin() + static_cast<long>(k + n));
      k += n;
    }
    if (scene.render.engine == scene::Engine::eevee)
      for (size_t k = f.views.size(); k-- > 0;) f.first_view[static_cast<size_t>(f.views[k].light)] = static_cast<int>(k);
  }
  report.passes.push_back({"setup", ms_since(lap), {{"objects", f.opaque.size() + f.transparent.size()}}});
  lap = Clock::now();

  // --- shadow pass -------------------------------------------------------------------------
  // Memory stays bounded: many views share a smaller map (64 MiB of depth at most).
  int shadow_size = scene.render.shadow_map_size;
  if (!f.views.empty()) {
    while (shadow_size > 256 && size_t(shadow_size) * shadow_size * 4 * f.views.size() > (size_t{64} << 20)) shadow_size /= 2;
    if (!st.shadows || st.shadows->size != shadow_size || st.shadows->layers < static_cast<int>(f.views.size())) {
      st.shadows.reset();
      auto a = ShadowArray::create(shadow_size, static_cast<int>(f.views.size()));
      if (!a) return a.take_error();
      st.shadows = std::move(*a);
    }
    ShaderVariant depth_variant{"depth.vert", "depth.frag", {}};
    auto depth_program = st.programs.get(depth_variant);
    if (!depth_program) return depth_program.take_error();
    (*depth_program)->use();
    DepthState(st.convention).forward_pass();
    glViewport(0, 0, shadow_size, shadow_size);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    // Slope-scaled bias against acne; the shader adds a normal offset on top.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.5f, 2.0f);
    for (size_t k = 0; k < f.views.size(); ++k) {
      st.shadows->bind_layer(static_cast<int>(k));
      glClear(GL_DEPTH_BUFFER_BIT);
      FrameUniforms u;
      u.camera_from_world = f.views[k].light_from_world;
      u.projection = f.views[k].clip_from_light;
      for (const auto& item : everything) draw(item, **depth_program, u, false);
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    finish_pass("shadow", {{"views", f.views.size()}, {"size", shadow_size}, {"filterTaps", scene.render.shadow_filter_taps}});
  } else if (f.plan.shadows) {
    f.plan.shadows = false;  // nothing fitted: compile the variant without shadows
  }
  const auto bind_shadows = [&] {
    if (f.views.empty()) return;
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D_ARRAY, st.shadows->depth.get());
    glBindSampler(1, st.shadows->compare_sampler.get());
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D_ARRAY, st.shadows->depth.get());
    glBindSampler(2, st.shadows->raw_sampler.get());
  };

  // --- reflection pass: the lit ground from straight above --------------------------------
  if (f.plan.reflection && f.ground) {
    const int size = scene.render.reflection_map_size;
    if (!st.reflection || st.reflection->size != size) {
      st.reflection.reset();
      auto r = ReflectionMap::create(size);
      if (!r) return r.take_error();
      st.reflection = std::move(*r);
    }
    auto program = st.programs.get(lit_variant(scene, f.plan, true));
    if (!program) return program.take_error();
    const double half = scene.ground->size / 2, h = scene.ground->height;
    const glm::dmat4 top = glm::inverse(scene::object_matrix({0, 0, h + 1}, glm::dmat3(1.0), glm::dvec3(1)));
    const FrameUniforms u = frame_uniforms(f, top, projection(false, half, half, 0.5, 1.5, false, st.convention), true,
                                           st.convention, shadow_size);
    glBindFramebuffer(GL_FRAMEBUFFER, st.reflection->fbo.get());
    glViewport(0, 0, size, size);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    (*program)->use();
    upload(**program, u);
    bind_shadows();
    draw(*f.ground, **program, u, true);
    glBindTexture(GL_TEXTURE_2D, st.reflection->color.get());
    glGenerateMipmap(GL_TEXTURE_2D);
    finish_pass("reflection", {{"size", size}, {"levels", st.reflection->levels}});
  }

  // --- main pass ----------------------------------------------------------------------------
  if (!st.frame || st.frame->width != width || st.frame->height != height ||
      st.frame->samples != scene.render.samples) {
    st.frame.reset();
    auto t = FrameTargets::create(width, height, scene.render.samples);
    if (!t) return t.take_error();
    st.frame = std::move(*t);
  }
  {
    auto program = st.programs.get(lit_variant(scene, f.plan, false));
    if (!program) return program.take_error();
    const glm::dmat4 proj = camera_projection(f.camera, st.convention);
    const FrameUniforms u = frame_uniforms(f, f.camera.camera_from_world, proj,
                                           f.camera.type == scene::Projection::orthographic, st.convention, shadow_size);
    glBindFramebuffer(GL_FRAMEBUFFER, st.frame->hdr_fbo.get());
    glViewport(0, 0, width, height);
    DepthState(st.convention).camera_pass();
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    const glm::vec3 background = u.world;
    glClearColor(background.r, background.g, background.b, 1.f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    (*program)->use();
    upload(**program, u);
    set(**program, "uGroundHalfSize", static_cast<float>(scene.ground ? scene.ground->size / 2 : 1.0));
    if (st.reflection && f.plan.reflection) {
      set(**program, "uReflectionLevels", static_cast<float>(st.reflection->levels - 1));
      glActiveTexture(GL_TEXTURE3);
      glBindTexture(GL_TEXTURE_2D, st.reflection->color.get());
    }
    bind_shadows();
    for (const auto& item : f.opaque) draw(item, **program, u, true);
    if (f.ground) draw(*f.ground, **program, u, true);
    if (!f.transparent.empty()) {
      // Back to front by the distance of each object's origin; blended over what is behind.
      auto sorted = f.transparent;
      std::sort(sorted.begin(), sorted.end(), [&](const DrawItem& a, const DrawItem& b) {
        return (u.camera_from_world * a.world_from_object[3]).z < (u.camera_from_world * b.world_from_object[3]).z;
      });
      glEnable(GL_BLEND);
      glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
      glDepthMask(GL_FALSE);
      for (const auto& item : sorted) draw(item, **program, u, true);
      glDepthMask(GL_TRUE);
      glDisable(GL_BLEND);
    }
    for (GLuint unit : {1u, 2u}) glBindSampler(unit, 0);
    glActiveTexture(GL_TEXTURE0);
    finish_pass("main", {{"objects", f.opaque.size() + f.transparent.size()},
                         {"ground", f.ground.has_value()},
                         {"samples", st.frame->samples},
                         {"shaderVariant", lit_variant(scene, f.plan, false).key()}});
  }

  // --- view pass: resolve, then the view transform to display values ---------------------
  {
    const bool filmic = scene.render.view_transform == scene::ViewTransform::filmic;
    if (filmic)
      if (auto s = st.ensure_filmic(); !s) return s.take_error();
    glBindFramebuffer(GL_READ_FRAMEBUFFER, st.frame->hdr_fbo.get());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, st.frame->resolve_fbo.get());
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    ShaderVariant v{"view.vert", "view.frag", {}};
    if (filmic) v.defines["VIEW_FILMIC"] = "1";
    auto program = st.programs.get(v);
    if (!program) return program.take_error();
    glBindFramebuffer(GL_FRAMEBUFFER, st.frame->display_fbo.get());
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    (*program)->use();
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, st.frame->resolved.get());
    set(**program, "uRadiance", 0);
    if (filmic) {
      glActiveTexture(GL_TEXTURE4);
      glBindTexture(GL_TEXTURE_3D, st.filmic->cube.get());
      glActiveTexture(GL_TEXTURE5);
      glBindTexture(GL_TEXTURE_2D, st.filmic->curve.get());
      glActiveTexture(GL_TEXTURE0);
      set(**program, "uFilmicCube", 4);
      set(**program, "uFilmicCurve", 5);
      set(**program, "uLog2Range", glm::vec2(image::FilmicTables::kLog2Min, image::FilmicTables::kLog2Max));
      set(**program, "uCubeSize", static_cast<float>(image::FilmicTables::kCubeSize));
      set(**program, "uCurveSize", static_cast<float>(image::FilmicTables::kCurveSize));
    }
    glBindVertexArray(st.empty_vao.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    finish_pass("view", {{"transform", std::string(scene::to_string(scene.render.view_transform))}});
  }

  SceneRender out;
  out.image = image::Image::blank(width, height, image::PixelType::u8);
  {
    std::vector<std::uint8_t> bottom_up(out.image.bytes.size());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, st.frame->display_fbo.get());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
    for (int y = 0; y < height; ++y)
      std::memcpy(out.image.row(y), bottom_up.data() + static_cast<size_t>(height - 1 - y) * out.image.row_bytes(), out.image.row_bytes());
    if (options.keep_radiance) {
      out.radiance = image::Image::blank(width, height, image::PixelType::f32);
      std::vector<std::uint8_t> rows(out.radiance.bytes.size());
      glBindFramebuffer(GL_READ_FRAMEBUFFER, st.frame->resolve_fbo.get());
      glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, rows.data());
      for (int y = 0; y < height; ++y)
        std::memcpy(out.radiance.row(y), rows.data() + static_cast<size_t>(height - 1 - y) * out.radiance.row_bytes(), out.radiance.row_bytes());
    }
    report.passes.push_back({"readback", ms_since(lap), nlohmann::json::object()});
    lap = Clock::now();
  }

  // --- framing: which object owns each pixel; guard-band renders for objects leaving the frame
  if (f.plan.framing) {
    if (!st.ids || st.ids->width != width || st.ids->height != height) {
      st.ids.reset();
      auto t = IdTarget::create(width, height);
      if (!t) return t.take_error();
      st.ids = std::move(*t);
    }
    auto program = st.programs.get(ShaderVariant{"depth.vert", "depth.frag", {}});
    if (!program) return program.take_error();
    (*program)->use();
    FrameUniforms u;
    u.camera_from_world = f.camera.camera_from_world;
    u.projection = camera_projection(f.camera, st.convention);
    glBindFramebuffer(GL_FRAMEBUFFER, st.ids->fbo.get());
    glViewport(0, 0, width, height);
    DepthState(st.convention).camera_pass();
    glDisable(GL_BLEND);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const auto id_colour = [](int id) {
      return glm::vec4(static_cast<float>(id & 255) / 255.f, static_cast<float>((id >> 8) & 255) / 255.f, 0.f, 1.f);
    };
    for (const auto& item : everything) {
      const glm::vec4 c = item.object >= 0 ? id_colour(item.object + 1) : glm::vec4(0.f);
      glUniform4fv((*program)->uniform("uId"), 1, glm::value_ptr(c));
      draw(item, **program, u, false);
    }
    std::vector<std::uint8_t> ids(static_cast<size_t>(width) * height * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, ids.data());
    std::vector<long long> counts(scene.objects.size() + 1, 0);
    for (size_t p = 0; p < ids.size(); p += 4) {
      const size_t id = ids[p] + (size_t{ids[p + 1]} << 8);
      if (id < counts.size()) ++counts[id];
    }

    int guard_renders = 0;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
      ObjectFraming fr;
      fr.name = scene.objects[i].name;
      const auto item = std::find_if(everything.begin(), everything.end(), [&](const DrawItem& d) { return d.object == static_cast<int>(i); });
      fr.drawn = item != everything.end();
      if (fr.drawn) {
        const VertexFraming vf = frame_vertices(f.camera, item->world_from_object, item->mesh->mesh);
        fr.box = vf.box;
        fr.fully_visible = vf.all_inside;
        fr.behind_camera = vf.in_front == 0;
        fr.partly_behind_camera = vf.in_front > 0 && vf.in_front < vf.total;
        fr.visible_pixels = counts[i + 1];
        fr.image_coverage = static_cast<double>(counts[i + 1]) / (static_cast<double>(width) * height);
        if (vf.all_inside) {
          fr.fraction_in_frame = 1;
        } else if (!fr.behind_camera) {
          // Render the object alone with the frame shrunk to the middle of a larger target, and count
          // how much of it lands in the middle.
          double k = 1;
          if (vf.box) {
            const double cx = width / 2.0, cy = height / 2.0;
            k = std::max({std::abs(vf.box->min.x - cx) / cx, std::abs(vf.box->max.x - cx) / cx,
                          std::abs(vf.box->min.y - cy) / cy, std::abs(vf.box->max.y - cy) / cy, 1.0});
          }
          k = std::min(std::ceil(k * 1.05 * 4) / 4, 8.0);
          const double density = std::min(1.0, 2048.0 / (std::max(width, height) * k));
          const int gw = std::max(8, static_cast<int>(std::lround(width * k * density)));
          const int gh = std::max(8, static_cast<int>(std::lround(height * k * density)));
          if (!st.guard || st.guard->width != gw || st.guard->height != gh) {
            st.guard.reset();
            auto t = IdTarget::create(gw, gh);
            if (!t) return t.take_error();
            st.guard = std::move(*t);
          }
          glBindFramebuffer(GL_FRAMEBUFFER, st.guard->fbo.get());
          glViewport(0, 0, gw, gh);
          glDisable(GL_DEPTH_TEST);
          glClear(GL_COLOR_BUFFER_BIT);
          FrameUniforms g = u;
          glm::dmat4 shrink(1.0);
          shrink[0][0] = shrink[1][1] = 1 / k;
          g.projection = shrink * u.projection;
          glUniform4fv((*program)->uniform("uId"), 1, glm::value_ptr(glm::vec4(1.f)));
          draw(*item, **program, g, false);
          std::vector<std::uint8_t> mask(static_cast<size_t>(gw) * gh * 4);
          glReadPixels(0, 0, gw, gh, GL_RGBA, GL_UNSIGNED_BYTE, mask.data());
          const double x0 = gw * (0.5 - 0.5 / k), x1 = gw * (0.5 + 0.5 / k), y0 = gh * (0.5 - 0.5 / k), y1 = gh * (0.5 + 0.5 / k);
          long long inside = 0, total = 0;
          for (int y = 0; y < gh; ++y)
            for (int x = 0; x < gw; ++x)
              if (mask[(static_cast<size_t>(y) * gw + x) * 4] != 0) {
                ++total;
                if (x + 0.5 >= x0 && x + 0.5 < x1 && y + 0.5 >= y0 && y + 0.5 < y1) ++inside;
              }
          fr.fraction_in_frame = total > 0 ? static_cast<double>(inside) / total : 0;
          DepthState(st.convention).camera_pass();
          ++guard_renders;
        }
      }
      report.framing.push_back(fr);
    }
    finish_pass("framing", {{"guardBandRenders", guard_renders}});
  }

  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  report.total_ms = ms_since(start);
  out.report = std::move(report);
  return out;
}

nlohmann::json SceneReport::to_json(const scene::SceneDescription& scene) const {
  nlohmann::json passes_json = nlohmann::json::array();
  for (const auto& p : passes) passes_json.push_back({{"name", p.name}, {"ms", p.ms}, {"detail", p.detail}});
  nlohmann::json framing_json = nlohmann::json::array();
  for (const auto& f : framing) framing_json.push_back(scene_render::to_json(f));
  return {{"engine", scene::to_string(scene.render.engine)},
          {"viewTransform", scene::to_string(scene.render.view_transform)},
          {"width", scene.render.width},
          {"height", scene.render.height},
          {"passes", passes_json},
          {"features", features},
          {"framing", framing_json},
          {"camera",
           {{"horizontalFov", camera.horizontal_fov_degrees()},
            {"verticalFov", camera.vertical_fov_degrees()},
            {"type", camera.type == scene::Projection::perspective ? "perspective" : "orthographic"}}},
          {"depth", depth},
          {"totalMs", total_ms}};
}

}  // namespace shadelab::scene_render
