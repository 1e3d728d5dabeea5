// Direct reads against pixel buffers (gl::Readback) on the canonical job (bunny, specular, 9
// frames 640 x 480, 4x MSAA, the grid PNG encoded while the frames render, as a worker does), in
// one process, the two modes alternating job by job, each job a fragment shader not seen before.
// Prints each mode's p50 (job and readback) and the median of the pairs' ratios: what
// `gl::Readback`'s default per device rests on.
//
//   build/bench/readback_bench [PAIRS=20]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "bench_renderer.h"
#include "fresh_shader.h"
#include "image/grid.h"
#include "image/grid_png_encoder.h"
#include "render/presets.h"
#include "scene/mesh.h"

namespace {

using namespace shadelab;
using Clock = std::chrono::steady_clock;

struct Job {
  double total_ms = 0, readback_ms = 0;
};

Job one_job(gl::Readback mode, const scene::Mesh& bunny, unsigned serial) {
  const auto preset = *render::find_preset("specular");
  render::RenderRequest request{.vertex = preset.vertex, .fragment = preset.fragment};
  request.fragment.text = bench::with_fresh_branch(request.fragment.text, serial);
  bench::renderer().set_readback(mode);
  const auto start = Clock::now();
  image::GridPngEncoder grid(image::GridLayout::for_frames(request.frames, request.width, request.height), request.frames);
  auto report = bench::renderer().render(request, bunny, [&](int k, const image::Image& f, bool opaque) { grid.add_frame(k, f, opaque); });
  auto png = report ? grid.finish() : Expected<std::vector<std::uint8_t>>(report.error());
  if (!png) {
    std::fprintf(stderr, "readback_bench: %s\n", png.error().format().c_str());
    std::exit(1);
  }
  return {std::chrono::duration<double, std::milli>(Clock::now() - start).count(), report->times.readback_ms};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int pairs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 20;
  const auto bunny = scene::builtin_mesh("bunny");
  if (!bunny) return 1;
  unsigned serial = std::random_device{}() % 100000000u;
  for (auto mode : {gl::Readback::direct, gl::Readback::pixel_buffer}) one_job(mode, *bunny, serial++);  // warm both paths
  std::vector<double> direct, buffered, direct_read, buffered_read, ratios;
  for (int i = 0; i < pairs; ++i) {
    const bool direct_first = i % 2 == 0;
    const Job a = one_job(direct_first ? gl::Readback::direct : gl::Readback::pixel_buffer, *bunny, serial++);
    const Job b = one_job(direct_first ? gl::Readback::pixel_buffer : gl::Readback::direct, *bunny, serial++);
    const Job& d = direct_first ? a : b;
    const Job& p = direct_first ? b : a;
    direct.push_back(d.total_ms);
    buffered.push_back(p.total_ms);
    direct_read.push_back(d.readback_ms);
    buffered_read.push_back(p.readback_ms);
    ratios.push_back(p.total_ms / d.total_ms);
  }
  std::printf("%s, %d pairs: direct p50 %.1f ms (readback %.1f), pixel buffers p50 %.1f ms (readback %.1f), "
              "pixel buffers / direct per pair: p50 %.3f\n",
              bench::renderer().context_info().gl_renderer.c_str(), pairs, median(direct), median(direct_read), median(buffered),
              median(buffered_read), median(ratios));
  return 0;
}
