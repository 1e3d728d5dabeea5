#include "course/unseen_roles.h"

#include <algorithm>
#include <regex>

namespace shadelab::course {

namespace {

using Rgb = std::array<double, 3>;

bool reads(const Preset& reference, const PageUniform& u) {
  return std::any_of(u.names.begin(), u.names.end(), [&](const std::string& name) {
    const std::regex word("\\b" + name + "\\b");
    return std::regex_search(reference.vertex.text, word) || std::regex_search(reference.fragment.text, word);
  });
}

Rgb rgb_of(const std::vector<double>& v) { return {v.size() > 0 ? v[0] : 0, v.size() > 1 ? v[1] : 0, v.size() > 2 ? v[2] : 0}; }

// What leaves the image as if the quantity were not there: the ambient term adds (black), the
// colours multiply (white). The light's position always shows.
std::optional<Rgb> as_if_absent(UniformRole role) {
  switch (role) {
    case UniformRole::ambient: return Rgb{0, 0, 0};
    case UniformRole::diffuse:
    case UniformRole::specular:
    case UniformRole::light_color: return Rgb{1, 1, 1};
    case UniformRole::light_position: return std::nullopt;
  }
  return std::nullopt;
}

std::string rgb_words(const Rgb& c) {
  char out[64];
  std::snprintf(out, sizeof out, "(%g, %g, %g)", c[0], c[1], c[2]);
  return out;
}

}  // namespace

std::vector<UnseenRole> unseen_roles(const Course& course) {
  std::vector<UnseenRole> out;
  for (const Checkpoint& k : course.checkpoints) {
    const Preset* reference = course.preset(k.reference);
    if (!reference) continue;
    for (const PageUniform& u : course.uniforms) {
      if (!u.role || !reads(*reference, u)) continue;
      const auto absent = as_if_absent(*u.role);
      if (!absent || rgb_of(u.value) != *absent) continue;
      // A probe's colour shows the light's colour; nothing a probe sets shows the others.
      const bool probe_shows = *u.role == UniformRole::light_color && std::any_of(k.probes.begin(), k.probes.end(), [&](const grade::Probe& p) {
        return p.light_color && Rgb{(*p.light_color)[0], (*p.light_color)[1], (*p.light_color)[2]} != *absent;
      });
      if (probe_shows) continue;
      out.push_back({k.name, *u.role,
                     u.names.front() + " is " + rgb_words(*absent) + " under the page's light and every probe of " + k.name +
                         ": a shader that leaves it out draws the same, and passes" +
                         (*u.role == UniformRole::light_color ? "; give a probe a lightColor" : "")});
    }
  }
  return out;
}

}  // namespace shadelab::course
