#include "scene/scene_mesh.h"

#include <array>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "core/words.h"
#include "scene/blender_convention.h"

namespace shadelab::scene {

namespace {

// Blender's UV sphere: `segments` around, `rings` from pole to pole, poles on Z.
Mesh blender_uv_sphere(int segments, int rings) {
  Mesh m;
  m.name = "uv_sphere";
  const auto point = [&](int ring, int seg) {
    const double theta = std::numbers::pi * ring / rings, phi = 2 * std::numbers::pi * seg / segments;
    return glm::dvec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
  };
  const auto add = [&](const glm::dvec3& p) {
    m.positions.push_back(glm::vec3(p));
    m.normals.push_back(glm::vec3(p));  // exact on the unit sphere
  };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const glm::dvec3 a = point(r, s), b = point(r + 1, s), c = point(r + 1, s + 1), d = point(r, s + 1);
      if (r > 0) add(a), add(b), add(d);          // the caps are triangle fans
      if (r < rings - 1) add(d), add(b), add(c);
    }
  m.normals_from_file = true;
  return m;
}

Mesh quads_to_mesh(const std::string& name, const std::vector<std::array<glm::vec3, 4>>& quads) {
  Mesh m;
  m.name = name;
  for (const auto& q : quads)
    for (int i : {0, 1, 2, 0, 2, 3}) m.positions.push_back(q[i]);
  apply_shading(m, Shading::flat);
  m.normals_from_file = true;
  return m;
}

Mesh blender_cube() {
  std::vector<std::array<glm::vec3, 4>> quads;
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {-1.f, 1.f}) {
      // Two tangents chosen so the quad winds counter-clockwise seen from outside.
      glm::vec3 n(0), u(0), v(0);
      n[axis] = sign;
      u[(axis + 1) % 3] = 1;
      v[(axis + 2) % 3] = sign;
      quads.push_back({n - u - v, n + u - v, n + u + v, n - u + v});
    }
  return quads_to_mesh("cube", quads);
}

Mesh blender_plane() { return quads_to_mesh("plane", {{{{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}}}); }

}  // namespace

std::vector<std::string> builtin_scene_mesh_names() { return {"suzanne", "uv_sphere", "cube", "plane", "teapot", "bunny"}; }

bool is_builtin_scene_mesh(const std::string& name) {
  for (const auto& n : builtin_scene_mesh_names())
    if (n == name) return true;
  return false;
}

Expected<Mesh> builtin_scene_mesh(const std::string& name) {
  if (name == "uv_sphere") return blender_uv_sphere(32, 16);
  if (name == "cube") return blender_cube();
  if (name == "plane") return blender_plane();
  if (name == "suzanne" || name == "teapot" || name == "bunny") {
    auto m = embedded_mesh("assets/" + name + ".obj", name);
    if (!m) return m;
    to_scene_space(*m, "obj");
    return m;
  }
  return make_error(ErrorCode::mesh_not_found, "there is no built-in scene mesh '" + name + "' (built-ins: " + comma_list(builtin_scene_mesh_names()) +
                                                   "; or an id from POST /api/meshes)");
}

void to_scene_space(Mesh& mesh, const std::string& extension) {
  if (!format_is_y_up(extension)) return;
  for (auto& p : mesh.positions) p = glm::vec3(y_up_to_z_up(glm::dvec3(p)));
  for (auto& n : mesh.normals) n = glm::vec3(y_up_to_z_up(glm::dvec3(n)));
}

void apply_shading(Mesh& mesh, Shading shading) {
  mesh.normals.resize(mesh.positions.size());
  if (shading == Shading::smooth) {
    if (!mesh.normals_from_file) compute_smooth_normals(mesh);
    return;
  }
  for (size_t t = 0; t + 2 < mesh.positions.size(); t += 3) {
    const glm::dvec3 a(mesh.positions[t]), b(mesh.positions[t + 1]), c(mesh.positions[t + 2]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double length = glm::length(n);
    const glm::vec3 face = length > 0 ? glm::vec3(n / length) : glm::vec3(0.f);  // zero area draws nothing
    mesh.normals[t] = mesh.normals[t + 1] = mesh.normals[t + 2] = face;
  }
}

}  // namespace shadelab::scene
