#include "scene_render/framing.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/type_ptr.hpp>

#include "scene_render/scene_passes.h"

namespace shadelab::scene_render {

VertexFraming frame_vertices(const scene::CameraModel& camera, const glm::dmat4& world_from_object, const scene::Mesh& mesh) {
  VertexFraming f;
  f.total = mesh.positions.size();
  const glm::dmat4 camera_from_object = camera.camera_from_world * world_from_object;
  PixelBox box{glm::dvec2(1e300), glm::dvec2(-1e300)};
  for (const auto& p : mesh.positions) {
    const glm::dvec3 c(camera_from_object * glm::dvec4(glm::dvec3(p), 1.0));
    const double depth = -c.z;
    const bool perspective = camera.type == scene::Projection::perspective;
    if (perspective && !(depth > 0)) {
      f.all_inside = false;
      continue;
    }
    ++f.in_front;
    const double x = perspective ? c.x / depth : c.x, y = perspective ? c.y / depth : c.y;
    const glm::dvec2 px((x / camera.plane.half_width + 1) * 0.5 * camera.width,
                        (1 - y / camera.plane.half_height) * 0.5 * camera.height);
    box.min = glm::min(box.min, px);
    box.max = glm::max(box.max, px);
    if (depth < camera.clip_start || depth > camera.clip_end || px.x < 0 || px.y < 0 || px.x > camera.width ||
        px.y > camera.height)
      f.all_inside = false;
  }
  if (f.in_front > 0) f.box = box;
  if (f.total == 0) f.all_inside = false;
  return f;
}

namespace {

// Object ids as colours: id + 1 in red (low byte) and green (high byte); 0 is no object.
glm::vec4 id_colour(int id) {
  return glm::vec4(static_cast<float>(id & 255) / 255.f, static_cast<float>((id >> 8) & 255) / 255.f, 0.f, 1.f);
}

template <class Target>
Status ensure_target(std::optional<Target>& target, int width, int height) {
  if (target && target->width == width && target->height == height) return Ok{};
  target.reset();
  auto t = Target::create(width, height);
  if (!t) return t.take_error();
  target = std::move(*t);
  return Ok{};
}

// Pixels each object owns in the image (index 0: none), from one render of object ids.
std::vector<long long> pixels_per_object(RenderState& st, const Frame& f, const SceneProgram& program, const FrameUniforms& u) {
  glBindFramebuffer(GL_FRAMEBUFFER, st.ids->fbo.get());
  glViewport(0, 0, f.width(), f.height());
  camera_depth_pass(st.convention);
  glDisable(GL_BLEND);
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  for (const auto& item : f.everything()) {
    const glm::vec4 c = item.object >= 0 ? id_colour(item.object + 1) : glm::vec4(0.f);
    glUniform4fv(program.uniform("uId"), 1, glm::value_ptr(c));
    draw(item, program, u, false);
  }
  std::vector<std::uint8_t> ids(static_cast<size_t>(f.width()) * f.height() * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, f.width(), f.height(), GL_RGBA, GL_UNSIGNED_BYTE, ids.data());
  std::vector<long long> counts(f.scene.objects.size() + 1, 0);
  for (size_t p = 0; p < ids.size(); p += 4) {
    const size_t id = ids[p] + (size_t{ids[p + 1]} << 8);
    if (id < counts.size()) ++counts[id];
  }
  return counts;
}

// The share of an object's projected area inside the frame: the object alone, rendered with the
// frame shrunk to the middle of a target k times larger, counting how much lands in the middle.
Expected<double> fraction_in_frame(RenderState& st, const Frame& f, const SceneProgram& program, const FrameUniforms& u,
                                   const DrawItem& item, const std::optional<PixelBox>& box) {
  const int width = f.width(), height = f.height();
  double k = 1;
  if (box) {
    const double cx = width / 2.0, cy = height / 2.0;
    k = std::max({std::abs(box->min.x - cx) / cx, std::abs(box->max.x - cx) / cx, std::abs(box->min.y - cy) / cy,
                  std::abs(box->max.y - cy) / cy, 1.0});
  }
  k = std::min(std::ceil(k * 1.05 * 4) / 4, 8.0);
  const double density = std::min(1.0, 2048.0 / (std::max(width, height) * k));
  const int gw = std::max(8, static_cast<int>(std::lround(width * k * density)));
  const int gh = std::max(8, static_cast<int>(std::lround(height * k * density)));
  if (auto s = ensure_target(st.guard, gw, gh); !s) return s.take_error();
  glBindFramebuffer(GL_FRAMEBUFFER, st.guard->fbo.get());
  glViewport(0, 0, gw, gh);
  glDisable(GL_DEPTH_TEST);
  glClear(GL_COLOR_BUFFER_BIT);
  FrameUniforms g = u;
  glm::dmat4 shrink(1.0);
  shrink[0][0] = shrink[1][1] = 1 / k;
  g.projection = shrink * u.projection;
  glUniform4fv(program.uniform("uId"), 1, glm::value_ptr(glm::vec4(1.f)));
  draw(item, program, g, false);
  std::vector<std::uint8_t> mask(static_cast<size_t>(gw) * gh * 4);
  glReadPixels(0, 0, gw, gh, GL_RGBA, GL_UNSIGNED_BYTE, mask.data());
  camera_depth_pass(st.convention);
  const double x0 = gw * (0.5 - 0.5 / k), x1 = gw * (0.5 + 0.5 / k), y0 = gh * (0.5 - 0.5 / k), y1 = gh * (0.5 + 0.5 / k);
  long long inside = 0, total = 0;
  for (int y = 0; y < gh; ++y)
    for (int x = 0; x < gw; ++x)
      if (mask[(static_cast<size_t>(y) * gw + x) * 4] != 0) {
        ++total;
        if (x + 0.5 >= x0 && x + 0.5 < x1 && y + 0.5 >= y0 && y + 0.5 < y1) ++inside;
      }
  return total > 0 ? static_cast<double>(inside) / total : 0.0;
}

}  // namespace

Expected<FramingDetail> framing_pass(RenderState& st, const Frame& f, std::vector<ObjectFraming>& framing) {
  if (auto s = ensure_target(st.ids, f.width(), f.height()); !s) return s.take_error();
  auto program = st.programs.get(ShaderVariant{"depth.vert", "depth.frag", {}});
  if (!program) return program.take_error();
  (*program)->use();
  FrameUniforms u;
  u.camera_from_world = f.camera.camera_from_world;
  u.projection = camera_projection(f.camera, st.convention);
  const std::vector<long long> counts = pixels_per_object(st, f, **program, u);
  const auto everything = f.everything();
  const double image_pixels = static_cast<double>(f.width()) * f.height();
  FramingDetail detail;
  for (size_t i = 0; i < f.scene.objects.size(); ++i) {
    ObjectFraming fr;
    fr.name = f.scene.objects[i].name;
    const auto item = std::find_if(everything.begin(), everything.end(), [&](const DrawItem& d) { return d.object == static_cast<int>(i); });
    fr.drawn = item != everything.end();
    if (fr.drawn) {
      const VertexFraming vf = frame_vertices(f.camera, item->world_from_object, item->mesh->mesh);
      fr.box = vf.box;
      fr.fully_visible = vf.all_inside;
      fr.behind_camera = vf.in_front == 0;
      fr.partly_behind_camera = vf.in_front > 0 && vf.in_front < vf.total;
      fr.visible_pixels = counts[i + 1];
      fr.image_coverage = static_cast<double>(counts[i + 1]) / image_pixels;
      if (vf.all_inside) {
        fr.fraction_in_frame = 1;
      } else if (!fr.behind_camera) {
        auto fraction = fraction_in_frame(st, f, **program, u, *item, vf.box);
        if (!fraction) return fraction.take_error();
        fr.fraction_in_frame = *fraction;
        ++detail.guard_band_renders;
      }
    }
    framing.push_back(fr);
  }
  return detail;
}

}  // namespace shadelab::scene_render
