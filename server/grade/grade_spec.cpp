#include "grade/grade_spec.h"

namespace shadelab::grade {

std::vector<ProbeSetting> probe_settings(const GradeSpec& spec, const Probe& probe) {
  std::vector<ProbeSetting> out;
  if (const auto& at = probe.light_position)
    for (const std::string& name : spec.light_position_uniforms) out.push_back({name, "vec3", {(*at)[0], (*at)[1], (*at)[2]}});
  if (const auto& rgb = probe.light_color) {
    const ProbeUniform& u = spec.light_color_uniform;
    std::vector<double> value = {(*rgb)[0], (*rgb)[1], (*rgb)[2]};
    if (u.type == "vec4") value.push_back(1.0);  // the page's colours are opaque
    for (const std::string& name : u.names) out.push_back({name, u.type, value});
  }
  return out;
}

}  // namespace shadelab::grade
