#include "render/render_request.h"

#include <cmath>

namespace shadelab::render {

namespace {
Error invalid(std::string message) { return make_error(ErrorCode::invalid_argument, std::move(message)); }
}  // namespace

Status validate(const RenderRequest& r, const RenderLimits& limits) {
  if (r.width < 1 || r.width > limits.max_width || r.height < 1 || r.height > limits.max_height)
    return invalid("width and height must be between 1 and " + std::to_string(limits.max_width) + " x " +
                   std::to_string(limits.max_height) + "; got " + std::to_string(r.width) + " x " + std::to_string(r.height));
  if (r.frames < 1 || r.frames > limits.max_frames)
    return invalid("frames must be between 1 and " + std::to_string(limits.max_frames) + "; got " + std::to_string(r.frames));
  if (!std::isfinite(r.degrees_per_frame) || std::abs(r.degrees_per_frame) > 3600.0)
    return invalid("degreesPerFrame must be a finite number of at most 3600 degrees");
  if (r.msaa < 0 || r.msaa > 64) return invalid("msaa must be between 0 and 64 samples; got " + std::to_string(r.msaa));
  for (const auto& u : r.uniforms) {
    if (u.name.empty()) return invalid("a uniform needs a name");
    if (u.values.empty() || u.values.size() > 4096)
      return invalid("uniform '" + u.name + "' needs between 1 and 4096 numbers");
  }
  return Ok{};
}

Status check_sources(const RenderRequest& r, const RenderLimits& limits) {
  const shader::SourceLimits source_limits{limits.max_source_bytes};
  auto vs = shader::unwrap(r.vertex, shader::Stage::vertex, source_limits);
  if (!vs) return vs.take_error();
  auto fs = shader::unwrap(r.fragment, shader::Stage::fragment, source_limits);
  if (!fs) return fs.take_error();
  return shader::check_same_version(*vs, *fs, r.fragment);
}

}  // namespace shadelab::render
