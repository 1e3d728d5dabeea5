#include "render/render_request.h"

#include <cmath>
#include <cstdio>

namespace shadelab::render {

namespace {
Error invalid(std::string message) { return make_error(ErrorCode::invalid_argument, std::move(message)); }

// Exactly: two different values must never share a key.
void append_exact(std::string& key, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g,", v);
  key += buf;
}
}  // namespace

std::string pixel_identity(const RenderRequest& r) {
  std::string key = r.vertex.text + '\0' + r.fragment.text + '\0';
  for (const double v : {double(r.width), double(r.height), double(r.frames), r.degrees_per_frame, double(r.msaa),
                         double(r.pixel_type == image::PixelType::f32), double(r.semantics == FloatSemantics::ieee)})
    append_exact(key, v);
  if (r.sample_position) {
    key += "sample:";
    for (const double v : *r.sample_position) append_exact(key, v);
  }
  key += "angles:";
  for (const double a : r.angles) append_exact(key, a);
  const auto& c = r.page.camera;
  key += "camera:";
  for (const double v : {c.fov_y_degrees, c.near, c.far, c.mesh_translation.x, c.mesh_translation.y, c.mesh_translation.z})
    append_exact(key, v);
  for (const auto& u : r.page.uniforms) {
    key += "page:" + u.name + ':' + u.glsl_type + '=';
    for (int i = 0; i < u.components; ++i) append_exact(key, u.value[static_cast<size_t>(i)]);
  }
  for (const auto& u : r.uniforms) {
    key += "set:" + u.name + '=';
    for (const double v : u.values) append_exact(key, v);
    key += ';';
  }
  return key;
}

Status validate(const RenderRequest& r, const RenderLimits& limits) {
  if (r.width < 1 || r.width > limits.max_width || r.height < 1 || r.height > limits.max_height)
    return invalid("width and height must be between 1 and " + std::to_string(limits.max_width) + " x " +
                   std::to_string(limits.max_height) + "; got " + std::to_string(r.width) + " x " + std::to_string(r.height));
  if (r.frames < 1 || r.frames > limits.max_frames)
    return invalid("frames must be between 1 and " + std::to_string(limits.max_frames) + "; got " + std::to_string(r.frames));
  if (!std::isfinite(r.degrees_per_frame) || std::abs(r.degrees_per_frame) > 3600.0)
    return invalid("degreesPerFrame must be a finite number of at most 3600 degrees");
  if (!r.angles.empty() && r.angles.size() != static_cast<size_t>(r.frames))
    return invalid("angles must list one rotation per frame: " + std::to_string(r.frames) + " frames, " +
                   std::to_string(r.angles.size()) + " angles");
  for (const double a : r.angles)
    if (!std::isfinite(a) || std::abs(a) > 1e6) return invalid("each frame's angle must be a finite number of degrees");
  const auto& c = r.page.camera;
  if (!(c.fov_y_degrees > 0 && c.fov_y_degrees < 180) || !(c.near > 0 && c.far > c.near) || !std::isfinite(c.far))
    return invalid("the page's camera needs a field of view in (0, 180) degrees and 0 < near < far");
  if (r.msaa < 0 || r.msaa > 64) return invalid("msaa must be between 0 and 64 samples; got " + std::to_string(r.msaa));
  if (const auto& at = r.sample_position) {
    if (r.msaa != 0) return invalid("a sample position is for a render without MSAA (msaa 0)");
    for (const double v : *at)
      if (!(v >= 0 && v <= 1)) return invalid("a sample position must lie within the pixel: each coordinate in [0, 1]");
  }
  for (const auto& u : r.uniforms) {
    if (u.name.empty()) return invalid("a uniform needs a name");
    if (u.values.empty() || u.values.size() > 4096)
      return invalid("uniform '" + u.name + "' needs between 1 and 4096 numbers");
  }
  return Ok{};
}

double frame_angle(const RenderRequest& r, int k) { return r.angles.empty() ? k * r.degrees_per_frame : r.angles[static_cast<size_t>(k)]; }

Status check_sources(const RenderRequest& r, const RenderLimits& limits) {
  const shader::SourceLimits source_limits{limits.max_source_bytes};
  auto vs = shader::unwrap(r.vertex, shader::Stage::vertex, source_limits);
  if (!vs) return vs.take_error();
  auto fs = shader::unwrap(r.fragment, shader::Stage::fragment, source_limits);
  if (!fs) return fs.take_error();
  return shader::check_same_version(*vs, *fs, r.fragment);
}

}  // namespace shadelab::render
