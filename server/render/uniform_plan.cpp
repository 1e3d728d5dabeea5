#include "render/uniform_plan.h"

#include <cmath>

#include "render/homework_contract.h"

namespace shadelab::render {

namespace {

std::string base_name(const std::string& name) {
  const auto bracket = name.find('[');
  return bracket == std::string::npos ? name : name.substr(0, bracket);
}

const gl::ActiveVariable* find_active(const std::vector<gl::ActiveVariable>& active, const std::string& name) {
  for (const auto& u : active) {
    if (u.name == name) return &u;
    // GL reports an array as "lights[0]"; a request may name it "lights".
    if (u.name.ends_with("[0]") && base_name(u.name) == name) return &u;
  }
  return nullptr;
}

std::string describe_type(const gl::ActiveVariable& u) {
  std::string t(u.type.name);
  if (u.array_size > 1) t += "[" + std::to_string(u.array_size) + "]";
  return t;
}

Expected<std::vector<float>> check_values(const gl::ActiveVariable& u, const UniformSetting& s) {
  const auto type_error = [&](const std::string& why) {
    return make_error(ErrorCode::uniform_type_mismatch, "uniform '" + s.name + "' is a " + describe_type(u) +
                                                            " in the shader; " + why);
  };
  if (u.type.kind == gl::ScalarKind::other || u.type.kind == gl::ScalarKind::sampler)
    return type_error("values of this type cannot be set");
  const size_t needed = static_cast<size_t>(u.type.components) * static_cast<size_t>(u.array_size);
  if (s.values.size() != needed)
    return type_error(std::to_string(s.values.size()) + (s.values.size() == 1 ? " number was" : " numbers were") +
                      " given, " + std::to_string(needed) + " are needed");
  std::vector<float> out;
  out.reserve(needed);
  for (double v : s.values) {
    switch (u.type.kind) {
      case gl::ScalarKind::bool_:
        if (v != 0.0 && v != 1.0) return type_error("a bool takes 0 or 1 (false or true)");
        break;
      case gl::ScalarKind::int_:
        if (!std::isfinite(v) || std::trunc(v) != v || std::abs(v) > 2147483647.0)
          return type_error("an integer type takes whole numbers");
        break;
      case gl::ScalarKind::uint_:
        if (!std::isfinite(v) || std::trunc(v) != v || v < 0 || v > 4294967295.0)
          return type_error("an unsigned type takes non-negative whole numbers");
        break;
      default: break;
    }
    out.push_back(static_cast<float>(v));
  }
  return out;
}

}  // namespace

Expected<UniformPlan> plan_uniforms(const std::vector<gl::ActiveVariable>& active, const std::vector<ConstantUniform>& page,
                                    const std::vector<UniformSetting>& settings) {
  UniformPlan plan;
  std::vector<const gl::ActiveVariable*> set_by_request;

  for (const auto& s : settings) {
    const gl::ActiveVariable* u = find_active(active, s.name);
    if (!u) {
      plan.warnings.push_back("uniform '" + s.name + "' is not used by the program; its value was ignored");
      continue;
    }
    auto values = check_values(*u, s);
    if (!values) return values.take_error();
    plan.constant.push_back({u, std::move(*values)});
    set_by_request.push_back(u);
  }
  const auto requested = [&](const gl::ActiveVariable* u) {
    for (const auto* r : set_by_request)
      if (r == u) return true;
    return false;
  };

  for (const auto& d : page) {
    const gl::ActiveVariable* u = find_active(active, d.name);
    if (!u || requested(u)) continue;
    if (u->type.name != d.glsl_type || u->array_size != 1) {
      plan.warnings.push_back("uniform '" + d.name + "' is declared " + describe_type(*u) +
                              ", but the homework page sets it as a " + d.glsl_type +
                              "; the browser leaves it at zero, and so does this render");
      continue;
    }
    plan.constant.push_back({u, std::vector<float>(d.value.begin(), d.value.begin() + d.components)});
  }

  const auto per_frame = [&](const char* name, const gl::ActiveVariable*& slot) {
    const gl::ActiveVariable* u = find_active(active, name);
    if (!u) return;
    if (requested(u)) {
      if (std::string_view(name) != kWorldToClip)
        plan.warnings.push_back(std::string("uniform '") + name + "' is set by the request, so it is the same in every frame");
      return;
    }
    if (u->type.name != "mat4" || u->array_size != 1) {
      plan.warnings.push_back(std::string("uniform '") + name + "' is declared " + describe_type(*u) +
                              ", but the homework page sets it as a mat4; the browser leaves it at zero, and so "
                              "does this render");
      return;
    }
    slot = u;
  };
  per_frame(kWorldToClip, plan.world_to_clip);
  per_frame(kMeshToWorld, plan.mesh_to_world);
  per_frame(kMeshToWorldRot, plan.mesh_to_world_rot);
  return plan;
}

}  // namespace shadelab::render
