#pragma once
// Inside the scene renderer: the state it keeps between renders, what one render draws, and one
// function per pass. scene_renderer.cpp runs them in order; framing.cpp measures the framing.
#include <GLES3/gl32.h>
#include <GLES2/gl2ext.h>  // after gl32.h, which defines what it needs

#include <array>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "gl/mesh_buffer.h"
#include "scene/pass_plan.h"
#include "scene_render/depth_convention.h"
#include "scene_render/gpu_resources.h"
#include "scene_render/scene_program.h"
#include "scene_render/scene_renderer.h"
#include "scene_render/shadow_views.h"

namespace shadelab::scene_render {

struct GpuMesh {
  scene::Mesh mesh;
  gl::MeshBuffer buffer;
  Aabb bounds;  // object space
};

// One object as the passes draw it: which mesh, where, with what material. The mesh is shared
// with the renderer's cache, so a mesh evicted from the cache mid-render stays alive until the
// render that draws it is over.
struct DrawItem {
  int object = -1;  // index into scene.objects; -1 for the ground
  std::shared_ptr<const GpuMesh> mesh;
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

// Everything one render draws, so the passes read as a list.
struct Frame {
  const scene::SceneDescription& scene;
  scene::PassPlan plan;
  scene::CameraModel camera;
  std::vector<DrawItem> opaque, transparent;
  std::optional<DrawItem> ground;
  std::vector<ShadowView> views;
  std::vector<int> first_view;      // per light: its first shadow view, or -1
  Aabb bounds;                      // everything drawn, world space
  glm::dvec3 workbench_light{0.0};  // the way Workbench's shadow light travels (world)
  int shadow_size = 0;              // texels per side of each shadow view, once the shadow pass chose it

  int width() const { return scene.render.width; }
  int height() const { return scene.render.height; }
  std::vector<DrawItem> everything() const;  // opaque, transparent, then the ground
};

// What a SceneRenderer keeps warm between renders: programs, meshes, targets, Filmic's tables.
struct RenderState {
  DepthConvention convention;
  PFNGLCLIPCONTROLEXTPROC clip_control = nullptr;
  ProgramCache programs;
  std::map<std::string, std::shared_ptr<const GpuMesh>> meshes;  // reference + shading
  std::optional<FrameTargets> frame;
  std::optional<IdTarget> ids, guard;
  std::optional<ShadowArray> shadows;
  std::optional<ReflectionMap> reflection;
  std::optional<FilmicTextures> filmic;
  std::string filmic_error;
  gl::VertexArrayName empty_vao;

  Expected<std::shared_ptr<const GpuMesh>> mesh(const std::string& reference, scene::Shading shading, const MeshResolver& resolve);
  Status ensure_filmic();
  void bind_shadows(const Frame& f) const;
};

// Sets GL's depth state for a pass that draws from the scene camera (reversed-Z where it can) or
// from a light (forward).
void camera_depth_pass(const DepthConvention& c);
void forward_depth_pass();

void draw(const DrawItem& item, const SceneProgram& program, const FrameUniforms& u, bool lit);
FrameUniforms frame_uniforms(const Frame& f, const glm::dmat4& camera_from_world, const glm::dmat4& projection,
                             bool orthographic, const DepthConvention& convention);

// The passes, in the order they run. Each leaves its result in the state's targets.
Expected<Frame> setup_pass(RenderState& st, const scene::SceneDescription& scene, const MeshResolver& resolve);
Expected<ShadowDetail> shadow_pass(RenderState& st, Frame& f);
Expected<ReflectionDetail> reflection_pass(RenderState& st, const Frame& f);
Expected<MainDetail> main_pass(RenderState& st, const Frame& f);
Expected<ViewDetail> view_pass(RenderState& st, const Frame& f);
void readback_pass(const RenderState& st, const Frame& f, bool keep_radiance, SceneRender& out);
// framing.cpp: which object owns each pixel, and guard-band renders for objects leaving the frame.
Expected<FramingDetail> framing_pass(RenderState& st, const Frame& f, std::vector<ObjectFraming>& framing);

}  // namespace shadelab::scene_render
