#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>

#include "core/words.h"
#include "cli/commands.h"
#include "cli/course_option.h"
#include "course/course_reader.h"
#include "cli/environment.h"
#include "cli/file_output.h"
#include "core/number_list.h"
#include "image/encode.h"
#include "image/grid.h"
#include "image/grid_png_encoder.h"
#include "render/renderer.h"

namespace shadelab::cli {

namespace {

// Unset facts (empty, nullopt) are the course's.
struct RenderFlags {
  std::string course;
  std::string vert, frag, preset, mesh;
  bool fit = false;
  std::optional<int> frames, msaa;
  std::optional<double> degrees;
  std::vector<double> angles;
  std::string size;
  std::vector<std::string> uniforms;
  std::string grid, frames_dir, prefix, format = "png";
  bool software = software_from_environment();
  bool timings = false;
  std::string readback = "auto";
};

Expected<shader::ShaderFile> read_shader(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::io_error, "cannot read shader file '" + path + "'");
  return shader::ShaderFile{path, std::string{std::istreambuf_iterator<char>(in), {}}};
}

Expected<render::UniformSetting> parse_uniform(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    return make_error(ErrorCode::invalid_argument, "--uniform takes NAME=v1,v2,...; got '" + text + "'");
  const std::string name = text.substr(0, eq);
  auto values = parse_number_list(std::string_view(text).substr(eq + 1), "--uniform " + name, {.booleans = true});
  if (!values) return values.take_error();
  return render::UniformSetting{name, std::move(*values)};
}

Status write_file(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
  return cli::write_file(path, {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
}

// The request's shaders (a preset, or the files given) and the frames' prefix.
Status read_shaders(const RenderFlags& f, const course::Course& c, render::RenderRequest& request, std::string& prefix) {
  if (!f.preset.empty() || (f.vert.empty() && f.frag.empty())) {
    if (!f.vert.empty() || !f.frag.empty())
      return make_error(ErrorCode::invalid_argument, "give either --preset or --vert and --frag, not both");
    auto found = c.find_preset(f.preset.empty() ? c.default_preset : f.preset);
    if (!found) return found.take_error();
    if (found->alias) std::cerr << "note: " << found->alias->note << "\n";
    request.vertex = found->preset->vertex;
    request.fragment = found->preset->fragment;
    // The frames of a deliverable's reference are named as the deliverable's are.
    if (prefix.empty()) prefix = found->preset->name;
    for (const auto& checkpoint : c.checkpoints)
      if (prefix == found->preset->name && checkpoint.reference == found->preset->name) prefix = checkpoint.prefix;
    return Ok{};
  }
  if (f.vert.empty() || f.frag.empty()) return make_error(ErrorCode::invalid_argument, "--vert and --frag must be given together");
  auto v = read_shader(f.vert);
  if (!v) return v.take_error();
  auto fr = read_shader(f.frag);
  if (!fr) return fr.take_error();
  request.vertex = std::move(*v);
  request.fragment = std::move(*fr);
  if (prefix.empty()) prefix = "render";
  return Ok{};
}

int run_render(const RenderFlags& f) {
  auto loaded = load_course(f.course);
  if (!loaded) return fail(loaded.error());
  const course::Course& c = **loaded;
  render::RenderRequest request = c.render_request({}, {});
  std::string prefix = f.prefix;
  if (auto s = read_shaders(f, c, request, prefix); !s) return fail(s.error());
  if (!f.size.empty())
    if (auto s = parse_size(f.size, "--size", request.width, request.height); !s) return fail(s.error());
  request.frames = f.frames.value_or(request.frames);
  request.degrees_per_frame = f.degrees.value_or(request.degrees_per_frame);
  if (!f.angles.empty()) {
    request.angles = f.angles;
    request.frames = static_cast<int>(f.angles.size());
  }
  request.msaa = f.msaa.value_or(request.msaa);
  const bool exr = f.format == "exr";
  request.pixel_type = exr ? image::PixelType::f32 : image::PixelType::u8;
  for (const auto& u : f.uniforms) {
    auto s = parse_uniform(u);
    if (!s) return fail(s.error());
    request.uniforms.push_back(std::move(*s));
  }
  if (auto valid = render::validate(request, render::RenderLimits{}); !valid) return fail(valid.error());

  auto mesh = load_mesh_argument(c, f.mesh.empty() ? c.default_mesh : f.mesh, f.fit);
  if (!mesh) return fail(mesh.error());
  auto renderer = render::Renderer::create({.force_software = f.software});
  if (!renderer) return fail(renderer.error());
  if (f.readback != "auto") renderer->set_readback(f.readback == "direct" ? gl::Readback::direct : gl::Readback::pixel_buffer);

  const std::string grid_path = f.grid.empty() && f.frames_dir.empty() ? "grid." + f.format : f.grid;
  const auto layout = image::GridLayout::for_frames(request.frames, request.width, request.height);
  // PNG grids are encoded while later frames render; frames and EXR grids are written at the end.
  std::optional<image::GridPngEncoder> grid_png;
  if (!grid_path.empty() && !exr) grid_png.emplace(layout, request.frames);
  std::vector<image::Image> frames;
  auto report = renderer->render(request, *mesh, [&](int k, const image::Image& frame, bool opaque) {
    if (grid_png) grid_png->add_frame(k, frame, opaque);
    if (!f.frames_dir.empty() || (exr && !grid_path.empty())) frames.push_back(frame);
  });
  if (!report) return fail(report.error());
  for (const auto& w : report->warnings) std::cerr << "warning: " << w << "\n";

  if (!grid_path.empty()) {
    auto bytes = exr ? image::encode_exr(image::compose_grid(layout, frames)) : grid_png->finish();
    if (!bytes) return fail(bytes.error());
    if (auto s = write_file(grid_path, *bytes); !s) return fail(s.error());
    std::cerr << "wrote " << grid_path << " (" << layout.width() << "x" << layout.height() << ", " << request.frames
              << " frames)\n";
  }
  if (!f.frames_dir.empty()) {
    std::filesystem::create_directories(f.frames_dir);
    for (size_t k = 0; k < frames.size(); ++k) {
      auto bytes = exr ? image::encode_exr(frames[k]) : image::encode_png(frames[k]);
      if (!bytes) return fail(bytes.error());
      const auto path = std::filesystem::path(f.frames_dir) / c.frame_file(prefix, static_cast<int>(k), f.format);
      if (auto s = write_file(path, *bytes); !s) return fail(s.error());
    }
    std::cerr << "wrote " << frames.size() << " frames to " << f.frames_dir << "/" << c.frame_file(prefix, 0, f.format) << " ... "
              << c.frame_file(prefix, static_cast<int>(frames.size()) - 1, f.format) << "\n";
  }
  if (f.timings) {
    const auto& t = report->times;
    std::cerr << "renderer: " << renderer->context_info().gl_renderer << ", " << report->samples << " samples\n"
              << "compile " << t.compile_ms << " ms, upload " << t.upload_ms << " ms, first frame " << t.first_frame_ms
              << " ms, render " << t.render_ms << " ms, readback " << t.readback_ms << " ms ("
              << (renderer->readback() == gl::Readback::direct ? "direct" : "pixel buffers") << "), total " << t.total_ms << " ms\n";
  }
  return 0;
}

}  // namespace

Command add_render_command(CLI::App& app) {
  auto flags = std::make_shared<RenderFlags>();
  auto* cmd = app.add_subcommand("render", "Render the spinning-mesh frames and the 3x3 grid");
  add_shader_options(cmd, flags->vert, flags->frag);
  const course::Course& builtin = course::builtin_course();
  add_course_option(cmd, flags->course);
  cmd->add_option("--preset", flags->preset, "Reference shaders of the course (built-in: " + comma_list(builtin.preset_names()) +
                                                 "; default " + builtin.default_preset + ")");
  cmd->add_option("--mesh", flags->mesh, "A mesh of the course (built-in: " + comma_list(builtin.mesh_names()) + "; default " +
                                             builtin.default_mesh + ") or a mesh file (OBJ, PLY, STL, glTF/GLB)");
  cmd->add_flag("--fit", flags->fit, "Scale and place the mesh as the course's default mesh stands (its height, base and centre)");
  cmd->add_option("--frames", flags->frames, "Number of frames (default: the course's, " + std::to_string(builtin.frames) + ")");
  cmd->add_option("--degrees", flags->degrees, "Rotation per frame about +Y, in degrees (default: the course's)");
  cmd->add_option("--angles", flags->angles,
                  "Each frame's rotation in degrees, instead of k x --degrees: where a page on a running clock drew them "
                  "(0,19.8,39.7,...), as a saved frames' grade reports")
      ->delimiter(',');
  cmd->add_option("--size", flags->size, "Frame size WIDTHxHEIGHT (default: the course's canvas, " + std::to_string(builtin.width) +
                                             "x" + std::to_string(builtin.height) + ")");
  cmd->add_option("--msaa", flags->msaa, "Samples per pixel (default: the course's canvas, " + std::to_string(builtin.msaa) + "; 0 = off)");
  cmd->add_option("--uniform", flags->uniforms, "Set a uniform: NAME=v1,v2,... (repeatable)");
  cmd->add_option("--grid", flags->grid, "Write the grid image here (default grid.png when no other output is given)");
  cmd->add_option("--frames-dir", flags->frames_dir, "Write each frame as DIR/" + builtin.frame_name + ".png (the course's names)");
  cmd->add_option("--prefix", flags->prefix, "IMAGE_PREFIX for frame names (default: the preset's checkpoint prefix, or its name)");
  cmd->add_option("--format", flags->format, "png (as the browser saves) or exr (float, exact)")
      ->check(CLI::IsMember({"png", "exr"}))
      ->capture_default_str();
  add_software_option(cmd, flags->software);
  cmd->add_flag("--timings", flags->timings, "Print the time of each phase");
  cmd->add_option("--readback", flags->readback,
                  "How frames leave the driver: direct (glReadPixels into memory), pixel-buffer (a pixel pack buffer "
                  "and a fence per frame), or auto (pixel buffers on a GPU, direct on llvmpipe)")
      ->check(CLI::IsMember({"auto", "direct", "pixel-buffer"}))
      ->capture_default_str();
  return [flags] { return run_render(*flags); };
}

}  // namespace shadelab::cli
