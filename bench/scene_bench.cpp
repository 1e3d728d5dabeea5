// The homework's two-objects scene: warm render time per pass, and image quality against
// Blender's Cycles at 256 samples, with the shadow knobs swept (map size, filter taps).
//
//   build/bench/scene_bench [--reference DIR] [--repeats N]
//
// DIR holds scene_cycles_256.png and scene_eevee.png (the course's Blender renders; default
// bench/reference/ in the source tree). Prints Markdown for docs/scenes.md.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <optional>
#include <map>
#include <string>
#include <vector>

#include "core/embedded_files.h"
#include "egl/headless_context.h"
#include "image/metrics.h"
#include "scene/scene_description.h"
#include "scene_render/scene_renderer.h"
#include "stats.h"

using namespace shadelab;

namespace {
using shadelab::bench::median;

std::optional<image::Image> read_rgba8(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return std::nullopt;
  const auto& spec = in->spec();
  image::Image img = image::Image::blank(spec.width, spec.height, image::PixelType::u8);
  std::vector<std::uint8_t> px(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, px.data())) return std::nullopt;
  for (size_t i = 0; i < size_t(spec.width) * spec.height; ++i)
    for (int c = 0; c < 4; ++c)
      img.bytes[i * 4 + c] = c < spec.nchannels ? px[i * spec.nchannels + c] : (c == 3 ? 255 : px[i * spec.nchannels]);
  return img;
}

struct Timed {
  double total = 0;
  std::map<std::string, double> passes;
  image::Image image;
};

Timed run(scene_render::SceneRenderer& r, const scene::SceneDescription& s, int repeats) {
  std::vector<double> totals;
  std::map<std::string, std::vector<double>> passes;
  Timed t;
  (void)r.render(s, scene_render::resolve_builtin_mesh);  // warm: programs, meshes, targets
  for (int i = 0; i < repeats; ++i) {
    auto out = r.render(s, scene_render::resolve_builtin_mesh);
    if (!out) {
      std::fprintf(stderr, "render failed: %s\n", out.error().format().c_str());
      std::exit(1);
    }
    totals.push_back(out->report.total_ms);
    for (const auto& p : out->report.passes) passes[std::string(p.name())].push_back(p.ms);
    t.image = std::move(out->image);
  }
  t.total = median(totals);
  for (auto& [name, v] : passes) t.passes[name] = median(v);
  return t;
}

std::string psnr(const image::Image& a, const std::optional<image::Image>& b) {
  if (!b || a.width != b->width || a.height != b->height) return "n/a";
  const auto m = image::compare(a, *b);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", m.psnr.value_or(99.0));
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  std::string reference = std::string(SHADELAB_SOURCE_DIR) + "/bench/reference";
  int repeats = 15;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--reference")) reference = argv[i + 1];
    if (!std::strcmp(argv[i], "--repeats")) repeats = std::max(1, std::atoi(argv[i + 1]));
  }
  auto context = egl::HeadlessContext::create({});
  if (!context) return std::fprintf(stderr, "%s\n", context.error().format().c_str()), 1;
  auto renderer = scene_render::SceneRenderer::create();
  if (!renderer) return 1;
  const auto base_json = nlohmann::json::parse(*embedded_file("assets/scenes/two_objects.json"));
  const auto cycles = read_rgba8(reference + "/scene_cycles_256.png");
  const auto eevee = read_rgba8(reference + "/scene_eevee.png");
  const auto workbench = read_rgba8(reference + "/scene_workbench.png");

  std::printf("Machine: %s; renderer: %s; %d warm repeats, median.\n\n", context->info().gl_renderer.c_str(),
              context->info().software ? "software" : "hardware", repeats);
  std::printf("Blender's own renders against Cycles 256: Eevee %s dB, Workbench %s dB.\n\n",
              eevee && cycles ? psnr(*eevee, cycles).c_str() : "n/a", workbench && cycles ? psnr(*workbench, cycles).c_str() : "n/a");

  // The scene as given, then per-pass times.
  auto base = scene::parse_scene(base_json);
  const Timed t = run(*renderer, *base, repeats);
  std::printf("## Two objects on a plane, 640 x 480, Eevee-like, 4x MSAA, Filmic\n\n");
  std::printf("| pass | ms |\n|---|---:|\n");
  for (const auto& [name, ms] : t.passes) std::printf("| %s | %.1f |\n", name.c_str(), ms);
  std::printf("| **total (warm)** | **%.1f** |\n\nPSNR against Cycles 256: **%s dB**\n\n", t.total, psnr(t.image, cycles).c_str());

  // The accuracy knobs: what each costs and what it buys, against Cycles.
  std::printf("## Shadow and effect knobs (time vs PSNR against Cycles 256)\n\n");
  std::printf("| variant | total ms | shadow ms | main ms | PSNR dB |\n|---|---:|---:|---:|---:|\n");
  struct Variant {
    std::string name;
    std::function<void(nlohmann::json&)> edit;
  };
  const std::vector<Variant> variants = {
      {"no shadows", [](auto& j) { j["lights"][0]["castShadow"] = false; }},
      {"shadow map 512, 16 taps", [](auto& j) { j["render"]["shadowMapSize"] = 512; }},
      {"shadow map 1024, 16 taps", [](auto& j) { j["render"]["shadowMapSize"] = 1024; }},
      {"shadow map 2048, 16 taps (default)", [](auto&) {}},
      {"shadow map 4096, 16 taps", [](auto& j) { j["render"]["shadowMapSize"] = 4096; }},
      {"shadow map 2048, 4 taps", [](auto& j) { j["render"]["shadowFilterTaps"] = 4; }},
      {"shadow map 2048, 8 taps", [](auto& j) { j["render"]["shadowFilterTaps"] = 8; }},
      {"shadow map 2048, 32 taps", [](auto& j) { j["render"]["shadowFilterTaps"] = 32; }},
      {"shadow map 2048, 64 taps", [](auto& j) { j["render"]["shadowFilterTaps"] = 64; }},
      {"no ground reflection (roughness 0.5)", [](auto& j) { j["objects"][0]["material"]["roughness"] = 0.5; }},
      {"no subsurface", [](auto& j) { j["objects"][1]["material"]["subsurface"] = 0; }},
      {"no MSAA", [](auto& j) { j["render"]["samples"] = 0; }},
      {"Standard view transform", [](auto& j) { j["render"]["viewTransform"] = "standard"; }},
      {"Workbench engine", [](auto& j) { j["render"]["engine"] = "workbench"; }},
      {"no framing report", [](auto& j) { j["render"]["framing"] = false; }},
  };
  for (const auto& v : variants) {
    auto j = base_json;
    v.edit(j);
    auto s = scene::parse_scene(j);
    if (!s) return std::fprintf(stderr, "%s\n", s.error().message.c_str()), 1;
    const Timed r = run(*renderer, *s, std::max(3, repeats / 3));
    const auto pass = [&](const char* n) { return r.passes.count(n) ? r.passes.at(n) : 0.0; };
    std::printf("| %s | %.1f | %.1f | %.1f | %s |\n", v.name.c_str(), r.total, pass("shadow"), pass("main"), psnr(r.image, cycles).c_str());
  }
  return 0;
}
