#pragma once
// The canonical job every benchmark measures: the built-in course's own (its default preset on its
// default mesh, its canvas, frames and samples, the grid PNG): today the Stanford bunny, specular,
// 9 frames 512 x 512, 4x MSAA. A benchmark cannot go on without it, so a failure ends the process.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "course/course_reader.h"
#include "scene/mesh.h"

namespace shadelab::bench {

inline const course::Course& canonical_course() { return course::builtin_course(); }

inline const course::Preset& canonical_preset() {
  const auto& c = canonical_course();
  return *c.preset(c.default_preset);
}

// The course's job for the default preset.
inline render::RenderRequest canonical_request() {
  const auto& p = canonical_preset();
  return canonical_course().render_request(p.vertex, p.fragment);
}

inline const scene::Mesh& canonical_mesh() {
  static const scene::Mesh mesh = [] {
    const auto& c = canonical_course();
    auto loaded = course::load_course_mesh(*c.mesh(c.default_mesh));
    if (!loaded) {
      std::fprintf(stderr, "the course's default mesh does not load: %s\n", loaded.error().format().c_str());
      std::exit(1);
    }
    return std::move(*loaded);
  }();
  return mesh;
}

// "bunny, specular, 9 frames 512 x 512, 4x MSAA": what a table's heading says was measured.
inline std::string canonical_description() {
  const auto& c = canonical_course();
  return c.default_mesh + ", " + c.default_preset + ", " + std::to_string(c.frames) + " frames " + std::to_string(c.width) + " x " +
         std::to_string(c.height) + ", " + std::to_string(c.msaa) + "x MSAA";
}

}  // namespace shadelab::bench
