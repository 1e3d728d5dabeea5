#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>

#include <glm/vec3.hpp>

#include "cli/commands.h"
#include "cli/course_option.h"
#include "cli/file_output.h"
#include "cli/environment.h"
#include "egl/headless_context.h"
#include "image/encode.h"
#include "scene/dolly_zoom.h"
#include "scene/scene_mesh.h"
#include "scene_render/scene_renderer.h"
#include "worker/result.h"

namespace shadelab::cli {

namespace {

Expected<nlohmann::json> read_json(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::io_error, "cannot read '" + path + "'");
  const std::string text{std::istreambuf_iterator<char>(in), {}};
  auto j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded()) return make_error(ErrorCode::invalid_argument, path + " is not valid JSON");
  return j;
}

// A scene file's meshes: built-ins by name, anything else a file next to the scene.
scene_render::MeshResolver file_resolver(const std::filesystem::path& scene_dir) {
  return [scene_dir](const std::string& reference) -> Expected<scene::Mesh> {
    if (scene::is_builtin_scene_mesh(reference)) return scene::builtin_scene_mesh(reference);
    const std::filesystem::path path = std::filesystem::path(reference).is_absolute() ? std::filesystem::path(reference)
                                                                                      : scene_dir / reference;
    auto mesh = scene::load_mesh_file(path.string());
    if (!mesh) return mesh;
    scene::to_scene_space(*mesh, scene::mesh_format_of(path.string()));
    return mesh;
  };
}

glm::dvec3 parse_vec3(const std::vector<double>& v) { return {v.at(0), v.at(1), v.at(2)}; }

}  // namespace

Command add_scene_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("scene", "Render a Blender-like scene description (JSON) to a PNG");
  struct Flags {
    std::string file, output = "scene.png", report;
    bool software = software_from_environment();
    int repeat = 1;
  };
  auto flags = std::make_shared<Flags>();
  cmd->add_option("--repeat", flags->repeat, "Render this many times and report the last (warm) render")->check(CLI::Range(1, 1000));
  cmd->add_option("file", flags->file, "Scene JSON (docs/scenes.md); mesh paths are relative to it")->required();
  cmd->add_option("-o,--output", flags->output, "Where to write the PNG")->capture_default_str();
  cmd->add_option("--report", flags->report, "Write the report (passes, timings, framing) as JSON here; - for stdout");
  add_software_option(cmd, flags->software);
  return [flags] {
    auto j = read_json(flags->file);
    if (!j) return fail(j.error());
    auto description = scene::parse_scene(*j);
    if (!description) return fail(description.error());
    auto context = egl::HeadlessContext::create({.force_software = flags->software});
    if (!context) return fail(context.error());
    auto renderer = scene_render::SceneRenderer::create();
    if (!renderer) return fail(renderer.error());
    const auto resolver = file_resolver(std::filesystem::path(flags->file).parent_path());
    auto rendered = renderer->render(*description, resolver);
    for (int i = 1; i < flags->repeat && rendered; ++i) rendered = renderer->render(*description, resolver);
    if (!rendered) return fail(rendered.error());
    auto png = image::encode_png(rendered->image);
    if (!png) return fail(png.error());
    if (auto s = write_file(flags->output, {reinterpret_cast<const char*>(png->data()), png->size()}); !s) return fail(s.error());

    const nlohmann::json report = rendered->report;
    if (flags->report == "-") {
      std::cout << report.dump(2) << "\n";
    } else if (!flags->report.empty()) {
      if (auto s = write_file(flags->report, report.dump(2) + "\n"); !s) return fail(s.error());
    }
    std::cerr << "wrote " << flags->output << " (" << description->render.width << "x" << description->render.height << ", "
              << scene::to_string(description->render.engine) << ")\n";
    for (const auto& p : rendered->report.passes) std::cerr << "  " << p.name() << ": " << p.ms << " ms\n";
    std::cerr << "  total: " << rendered->report.total_ms << " ms\n";
    for (const auto& fr : rendered->report.framing)
      std::cerr << "  " << fr.name << ": " << (fr.fully_visible ? "fully visible" : "NOT fully visible") << ", "
                << fr.fraction_in_frame * 100 << "% in frame, covers " << fr.image_coverage * 100 << "% of the image\n";
    return 0;
  };
}

Command add_dolly_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("dolly", "Camera distances for a dolly zoom: keep a subject's size across lenses");
  struct Flags {
    std::vector<double> subject{0, 0, 0}, from{0, -4, 0}, lenses{25, 50, 100};
    double lens = 25;
  };
  auto flags = std::make_shared<Flags>();
  cmd->add_option("--subject", flags->subject, "Subject location x y z")->expected(3)->capture_default_str();
  cmd->add_option("--from", flags->from, "Reference camera location x y z")->expected(3)->capture_default_str();
  cmd->add_option("--lens", flags->lens, "Reference lens (mm)")->capture_default_str();
  cmd->add_option("--lenses", flags->lenses, "Lenses to solve for (mm)")->capture_default_str();
  return [flags] {
    for (const auto& s : scene::dolly_zoom(parse_vec3(flags->subject), parse_vec3(flags->from), flags->lens, flags->lenses))
      std::cout << s.lens_mm << " mm: distance " << s.distance << ", location [" << s.location.x << ", " << s.location.y
                << ", " << s.location.z << "]\n";
    return 0;
  };
}

}  // namespace shadelab::cli
