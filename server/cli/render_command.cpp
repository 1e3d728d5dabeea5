#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>

#include "cli/commands.h"
#include "cli/file_output.h"
#include "core/number_list.h"
#include "cli/environment.h"
#include "image/encode.h"
#include "image/grid.h"
#include "image/grid_png_encoder.h"
#include "render/presets.h"
#include "render/renderer.h"

namespace shadelab::cli {

namespace {

struct RenderFlags {
  std::string vert, frag, preset, mesh = "bunny";
  bool fit = false;
  int frames = 9;
  double degrees = 20.0;
  std::string size = "640x480";
  int msaa = 4;
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

Expected<scene::Mesh> load_mesh_arg(const RenderFlags& f) {
  const bool is_file = std::filesystem::exists(f.mesh) || f.mesh.find('.') != std::string::npos;
  auto mesh = is_file ? scene::load_mesh_file(f.mesh) : scene::builtin_mesh(f.mesh);
  if (mesh && f.fit) scene::fit_to_homework(*mesh);
  return mesh;
}

int run_render(const RenderFlags& f) {
  render::RenderRequest request;
  std::string prefix = f.prefix;
  if (!f.preset.empty() || (f.vert.empty() && f.frag.empty())) {
    if (!f.vert.empty() || !f.frag.empty())
      return fail(make_error(ErrorCode::invalid_argument, "give either --preset or --vert and --frag, not both"));
    const std::string name = f.preset.empty() ? "specular" : f.preset;
    const auto preset = render::find_preset(name);
    if (!preset)
      return fail(make_error(ErrorCode::unknown_preset,
                             "no preset '" + name + "' (presets: starter, smooth, gouraud, diffuse, specular)"));
    request.vertex = preset->vertex;
    request.fragment = preset->fragment;
    if (prefix.empty()) prefix = name;
  } else {
    if (f.vert.empty() || f.frag.empty())
      return fail(make_error(ErrorCode::invalid_argument, "--vert and --frag must be given together"));
    auto v = read_shader(f.vert);
    if (!v) return fail(v.error());
    auto fr = read_shader(f.frag);
    if (!fr) return fail(fr.error());
    request.vertex = std::move(*v);
    request.fragment = std::move(*fr);
    if (prefix.empty()) prefix = "render";
  }
  if (std::sscanf(f.size.c_str(), "%dx%d", &request.width, &request.height) != 2)
    return fail(make_error(ErrorCode::invalid_argument, "--size takes WIDTHxHEIGHT, e.g. 640x480; got '" + f.size + "'"));
  request.frames = f.frames;
  request.degrees_per_frame = f.degrees;
  request.msaa = f.msaa;
  const bool exr = f.format == "exr";
  request.pixel_type = exr ? image::PixelType::f32 : image::PixelType::u8;
  for (const auto& u : f.uniforms) {
    auto s = parse_uniform(u);
    if (!s) return fail(s.error());
    request.uniforms.push_back(std::move(*s));
  }
  if (auto valid = render::validate(request, render::RenderLimits{}); !valid) return fail(valid.error());

  auto mesh = load_mesh_arg(f);
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
      const auto path = std::filesystem::path(f.frames_dir) / ("hw2_" + prefix + "_" + std::to_string(k) + "." + f.format);
      if (auto s = write_file(path, *bytes); !s) return fail(s.error());
    }
    std::cerr << "wrote " << frames.size() << " frames to " << f.frames_dir << "/hw2_" << prefix << "_{0.." << frames.size() - 1
              << "}." << f.format << "\n";
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
  cmd->add_option("--vert", flags->vert, "Vertex shader: GLSL or the homework's JS module (phong_vert.js)");
  cmd->add_option("--frag", flags->frag, "Fragment shader: GLSL or JS module");
  cmd->add_option("--preset", flags->preset, "Reference shaders: starter, smooth, gouraud, diffuse, specular (default)");
  cmd->add_option("--mesh", flags->mesh, "Built-in mesh (bunny, teapot) or a mesh file (OBJ, PLY, STL, glTF/GLB)")
      ->capture_default_str();
  cmd->add_flag("--fit", flags->fit, "Scale and place the mesh like the built-ins (height 3.5, base at y = 0, centred)");
  cmd->add_option("--frames", flags->frames, "Number of frames")->capture_default_str();
  cmd->add_option("--degrees", flags->degrees, "Rotation per frame about +Y, in degrees")->capture_default_str();
  cmd->add_option("--size", flags->size, "Frame size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--msaa", flags->msaa, "Samples per pixel (the browser canvas: 4; 0 = off)")->capture_default_str();
  cmd->add_option("--uniform", flags->uniforms, "Set a uniform: NAME=v1,v2,... (repeatable)");
  cmd->add_option("--grid", flags->grid, "Write the grid image here (default grid.png when no other output is given)");
  cmd->add_option("--frames-dir", flags->frames_dir, "Write each frame as DIR/hw2_{prefix}_{k}.png");
  cmd->add_option("--prefix", flags->prefix, "IMAGE_PREFIX for frame names (default: the preset's name)");
  cmd->add_option("--format", flags->format, "png (as the browser saves) or exr (float, exact)")
      ->check(CLI::IsMember({"png", "exr"}))
      ->capture_default_str();
  cmd->add_flag("--software", flags->software, "Force Mesa's software renderer (also SHADELAB_SOFTWARE=1)");
  cmd->add_flag("--timings", flags->timings, "Print the time of each phase");
  cmd->add_option("--readback", flags->readback,
                  "How frames leave the driver: direct (glReadPixels into memory), pixel-buffer (a pixel pack buffer "
                  "and a fence per frame), or auto (pixel buffers on a GPU, direct on llvmpipe)")
      ->check(CLI::IsMember({"auto", "direct", "pixel-buffer"}))
      ->capture_default_str();
  return [flags] { return run_render(*flags); };
}

}  // namespace shadelab::cli
