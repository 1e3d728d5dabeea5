#include "cli/course_option.h"

#include <cstdio>
#include <filesystem>

#include "course/course_reader.h"

namespace shadelab::cli {

void add_course_option(CLI::App* command, std::string& path) {
  command->add_option("--course", path, "Course profile (JSON, docs/course-profile.md); default: the built-in " +
                                            course::builtin_course().id)
      ->envname("SHADELAB_COURSE");
}

void add_software_option(CLI::App* command, bool& software) {
  command->add_flag("--software", software, "Force Mesa's software renderer (also SHADELAB_SOFTWARE=1)");
}

void add_cache_option(CLI::App* command, std::string& folder) {
  command->add_option("--cache-dir", folder,
                      "Where reference renders are kept across runs, rendered once per course and checkpoint "
                      "(also SHADELAB_CACHE_DIR; an empty string keeps them in memory only)")
      ->capture_default_str();
}

void add_grader_options(CLI::App* command, std::string& course, std::string& cache_dir, bool& software) {
  add_course_option(command, course);
  add_cache_option(command, cache_dir);
  add_software_option(command, software);
}

void add_shader_options(CLI::App* command, std::string& vert, std::string& frag) {
  command->add_option("--vert", vert, "Vertex shader: GLSL or the homework's JS module (phong_vert.js)");
  command->add_option("--frag", frag, "Fragment shader: GLSL or JS module");
}

Expected<std::shared_ptr<const course::Course>> load_course(const std::string& path) {
  if (path.empty()) return std::shared_ptr<const course::Course>(&course::builtin_course(), [](const course::Course*) {});
  auto loaded = course::load_course_file(path);
  if (!loaded) return loaded.take_error();
  return std::shared_ptr<const course::Course>(std::make_shared<course::Course>(std::move(*loaded)));
}

Status parse_size(const std::string& text, const std::string& flag, int& width, int& height) {
  char end = 0;
  if (std::sscanf(text.c_str(), "%dx%d%c", &width, &height, &end) != 2)
    return make_error(ErrorCode::invalid_argument, flag + " takes WIDTHxHEIGHT, e.g. 512x512; got '" + text + "'");
  return Ok{};
}

Expected<scene::Mesh> load_mesh_argument(const course::Course& c, const std::string& name, bool fit) {
  const course::CourseMesh* builtin = c.mesh(name);
  const bool is_file = !builtin && (std::filesystem::exists(name) || name.find('.') != std::string::npos);
  if (!builtin && !is_file) {
    std::string names;
    for (const auto& n : c.mesh_names()) names += (names.empty() ? "" : ", ") + n;
    return make_error(ErrorCode::mesh_not_found, "no mesh '" + name + "' (the course's: " + names + "; or a mesh file)");
  }
  auto mesh = builtin ? course::load_course_mesh(*builtin) : scene::load_mesh_file(name);
  if (!mesh || !fit) return mesh;
  auto target = course::fit_bounds(c);
  if (!target) return target.take_error();
  scene::fit_to(*mesh, *target);
  return mesh;
}

}  // namespace shadelab::cli
