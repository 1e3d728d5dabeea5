#include "scene_render/scene_passes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "image/canvas_readback.h"
#include "image/view_transform.h"
#include "scene/scene_mesh.h"

namespace shadelab::scene_render {

namespace {

using scene::SceneDescription;

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

// The ground as the objects' lower hemisphere sees it: lit by every light and the world at the
// point under the objects (no shadows). Without a ground the world surrounds everything.
glm::dvec3 ground_bounce(const Frame& f) {
  const SceneDescription& s = f.scene;
  glm::dvec3 bounce = s.world.color * s.world.strength;
  if (!s.ground) return bounce;
  glm::dvec3 centre(0, 0, s.ground->height);
  if (!f.bounds.empty())
    centre = glm::dvec3(0.5 * (f.bounds.min.x + f.bounds.max.x), 0.5 * (f.bounds.min.y + f.bounds.max.y), s.ground->height);
  double e = 0;
  for (const auto& l : s.lights) e += irradiance(l, centre, {0, 0, 1});
  const scene::Material& g = s.ground->material;
  return g.base_color * (1 - g.metallic) * (e / std::numbers::pi) + g.base_color * (1 - g.metallic) * bounce;
}

void light_uniforms(const Frame& f, const glm::dmat4& camera_from_world, FrameUniforms& u) {
  const glm::dmat3 rotation(camera_from_world);
  const SceneDescription& s = f.scene;
  u.light_count = static_cast<int>(std::min<size_t>(s.lights.size(), kMaxLights));
  for (int i = 0; i < u.light_count; ++i) {
    const scene::Light& l = s.lights[static_cast<size_t>(i)];
    u.light_direction[i] = f3(glm::normalize(rotation * light_direction(l)));
    u.light_position[i] = f3(glm::dvec3(camera_from_world * glm::dvec4(l.location, 1.0)));
    double shape_x = l.radius, cos_outer = -2, blend = 1;
    double value = l.power_w / (4 * std::numbers::pi);  // point, spot: W -> W/sr
    switch (l.type) {
      case scene::LightType::sun:
        u.light_type[i] = 1;
        value = l.strength;
        shape_x = std::tan(l.angle_degrees * std::numbers::pi / 360);
        break;
      case scene::LightType::spot:
        u.light_type[i] = 2;
        cos_outer = std::cos(l.spot_size_degrees * std::numbers::pi / 360);
        blend = (1 - cos_outer) * l.spot_blend;  // Blender's spot blend, as a cosine width
        break;
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

// Draws the transparent objects back to front by the distance of each origin, blended over
// what is behind them.
void draw_transparent(const Frame& f, const SceneProgram& program, const FrameUniforms& u) {
  auto sorted = f.transparent;
  std::sort(sorted.begin(), sorted.end(), [&](const DrawItem& a, const DrawItem& b) {
    return (u.camera_from_world * a.world_from_object[3]).z < (u.camera_from_world * b.world_from_object[3]).z;
  });
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);
  for (const auto& item : sorted) draw(item, program, u, true);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
}

void bind_filmic(const RenderState& st, const SceneProgram& program) {
  glActiveTexture(GL_TEXTURE4);
  glBindTexture(GL_TEXTURE_3D, st.filmic->cube.get());
  glActiveTexture(GL_TEXTURE5);
  glBindTexture(GL_TEXTURE_2D, st.filmic->curve.get());
  glActiveTexture(GL_TEXTURE0);
  set(program, "uFilmicCube", 4);
  set(program, "uFilmicCurve", 5);
  set(program, "uLog2Range", glm::vec2(image::FilmicTables::kLog2Min, image::FilmicTables::kLog2Max));
  set(program, "uCubeSize", static_cast<float>(image::FilmicTables::kCubeSize));
  set(program, "uCurveSize", static_cast<float>(image::FilmicTables::kCurveSize));
}

}  // namespace

std::vector<DrawItem> Frame::everything() const {
  std::vector<DrawItem> all = opaque;
  all.insert(all.end(), transparent.begin(), transparent.end());
  if (ground) all.push_back(*ground);
  return all;
}

void camera_depth_pass(const DepthConvention& c) {
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(c.reversed ? GL_GREATER : GL_LESS);
  glClearDepthf(c.reversed ? 0.f : 1.f);
}

void forward_depth_pass() {
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glClearDepthf(1.f);
}

void RenderState::bind_shadows(const Frame& f) const {
  if (f.views.empty()) return;
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D_ARRAY, shadows->depth.get());
  glBindSampler(1, shadows->compare_sampler.get());
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D_ARRAY, shadows->depth.get());
  glBindSampler(2, shadows->raw_sampler.get());
}

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
                             bool orthographic, const DepthConvention& convention) {
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
  u.ground_bounce = f3(ground_bounce(f));
  if (s.ground) u.camera_from_ground = f3(glm::dvec3(world_from_camera[3]) - glm::dvec3(0, 0, s.ground->height));
  light_uniforms(f, camera_from_world, u);

  u.shadow_views = static_cast<int>(std::min<size_t>(f.views.size(), kMaxShadowViews));
  const glm::dmat4 to_texture = clip_to_texture(convention);
  for (int k = 0; k < u.shadow_views; ++k) {
    const ShadowView& v = f.views[static_cast<size_t>(k)];
    u.shadow_matrix[k] = glm::mat4(to_texture * v.clip_from_light * (v.light_from_world * world_from_camera));
    u.shadow_a[k] = glm::vec4(v.perspective ? 1.f : 0.f, v.near, v.far, v.light_size);
    u.shadow_b[k] = glm::vec4(v.half_extent, 2 * v.half_extent / f.shadow_size, 1.0 / f.shadow_size, 0);
  }
  u.workbench_direction = f3(-glm::normalize(rotation * f.workbench_light));
  return u;
}

Expected<ShadowDetail> shadow_pass(RenderState& st, Frame& f) {
  if (f.views.empty()) {
    f.plan.shadows = false;  // nothing fitted: compile the variant without shadows
    return ShadowDetail{};
  }
  // Memory stays bounded: many views share a smaller map (64 MiB of depth at most).
  int& size = f.shadow_size;
  while (size > 256 && size_t(size) * size * 4 * f.views.size() > (size_t{64} << 20)) size /= 2;
  if (!st.shadows || st.shadows->size != size || st.shadows->layers < static_cast<int>(f.views.size())) {
    st.shadows.reset();
    auto a = ShadowArray::create(size, static_cast<int>(f.views.size()));
    if (!a) return a.take_error();
    st.shadows = std::move(*a);
  }
  auto program = st.programs.get(ShaderVariant{"depth.vert", "depth.frag", {}});
  if (!program) return program.take_error();
  (*program)->use();
  forward_depth_pass();
  glViewport(0, 0, size, size);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  // Slope-scaled bias against acne; the shader adds a normal offset on top.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.5f, 2.0f);
  const auto everything = f.everything();
  for (size_t k = 0; k < f.views.size(); ++k) {
    st.shadows->bind_layer(static_cast<int>(k));
    glClear(GL_DEPTH_BUFFER_BIT);
    FrameUniforms u;
    u.camera_from_world = f.views[k].light_from_world;
    u.projection = f.views[k].clip_from_light;
    for (const auto& item : everything) draw(item, **program, u, false);
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
  return ShadowDetail{static_cast<int>(f.views.size()), size, f.scene.render.shadow_filter_taps};
}

// The lit ground from straight above, into a mipmapped map the main pass reads reflections from.
Expected<ReflectionDetail> reflection_pass(RenderState& st, const Frame& f) {
  const SceneDescription& scene = f.scene;
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
  const FrameUniforms u = frame_uniforms(f, top, projection(false, half, half, 0.5, 1.5, false, st.convention), true, st.convention);
  glBindFramebuffer(GL_FRAMEBUFFER, st.reflection->fbo.get());
  glViewport(0, 0, size, size);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  (*program)->use();
  upload(**program, u);
  st.bind_shadows(f);
  draw(*f.ground, **program, u, true);
  glBindTexture(GL_TEXTURE_2D, st.reflection->color.get());
  glGenerateMipmap(GL_TEXTURE_2D);
  return ReflectionDetail{size, st.reflection->levels};
}

// Every object lit, into the multisampled HDR target.
Expected<MainDetail> main_pass(RenderState& st, const Frame& f) {
  const SceneDescription& scene = f.scene;
  const int width = f.width(), height = f.height();
  if (!st.frame || st.frame->width != width || st.frame->height != height || st.frame->samples != scene.render.samples) {
    st.frame.reset();
    auto t = FrameTargets::create(width, height, scene.render.samples);
    if (!t) return t.take_error();
    st.frame = std::move(*t);
  }
  const ShaderVariant variant = lit_variant(scene, f.plan, false);
  auto program = st.programs.get(variant);
  if (!program) return program.take_error();
  const FrameUniforms u = frame_uniforms(f, f.camera.camera_from_world, camera_projection(f.camera, st.convention),
                                         f.camera.type == scene::Projection::orthographic, st.convention);
  glBindFramebuffer(GL_FRAMEBUFFER, st.frame->hdr_fbo.get());
  glViewport(0, 0, width, height);
  camera_depth_pass(st.convention);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glClearColor(u.world.r, u.world.g, u.world.b, 1.f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  (*program)->use();
  upload(**program, u);
  set(**program, "uGroundHalfSize", static_cast<float>(scene.ground ? scene.ground->size / 2 : 1.0));
  if (st.reflection && f.plan.reflection) {
    set(**program, "uReflectionLevels", static_cast<float>(st.reflection->levels - 1));
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, st.reflection->color.get());
  }
  st.bind_shadows(f);
  for (const auto& item : f.opaque) draw(item, **program, u, true);
  if (f.ground) draw(*f.ground, **program, u, true);
  if (!f.transparent.empty()) draw_transparent(f, **program, u);
  for (GLuint unit : {1u, 2u}) glBindSampler(unit, 0);
  glActiveTexture(GL_TEXTURE0);
  return MainDetail{static_cast<int>(f.opaque.size() + f.transparent.size()), f.ground.has_value(), st.frame->samples, variant.key()};
}

// Resolves the multisampled radiance, then the view transform to display values.
Expected<ViewDetail> view_pass(RenderState& st, const Frame& f) {
  const SceneDescription& scene = f.scene;
  const int width = f.width(), height = f.height();
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
  if (filmic) bind_filmic(st, **program);
  glBindVertexArray(st.empty_vao.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  return ViewDetail{scene.render.view_transform};
}

void readback_pass(const RenderState& st, const Frame& f, bool keep_radiance, SceneRender& out) {
  const int width = f.width(), height = f.height();
  out.image = image::Image::blank(width, height, image::PixelType::u8);
  std::vector<std::uint8_t> rows(out.image.bytes.size());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, st.frame->display_fbo.get());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  image::flip_from_readback(rows.data(), out.image);
  if (!keep_radiance) return;
  out.radiance = image::Image::blank(width, height, image::PixelType::f32);
  rows.resize(out.radiance.bytes.size());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, st.frame->resolve_fbo.get());
  glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, rows.data());
  image::flip_from_readback(rows.data(), out.radiance);
}

}  // namespace shadelab::scene_render
