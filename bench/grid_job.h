#pragma once
// The canonical job (canonical_job.h) in process, shaped as a worker runs it: with a fragment
// shader not seen before, the frames rendered, the grid PNG encoded while they render. A
// benchmark cannot go on past an error, so one ends the process with the reason.
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "bench_renderer.h"
#include "canonical_job.h"
#include "fresh_shader.h"
#include "image/grid.h"
#include "image/grid_png_encoder.h"
#include "scene/mesh.h"

namespace shadelab::bench {

// The canonical request with a fresh fragment shader; at another size when one is given.
inline render::RenderRequest fresh_canonical(unsigned serial, int width = 0, int height = 0) {
  render::RenderRequest r = canonical_request();
  if (width > 0) r.width = width, r.height = height;
  r.fragment.text = with_fresh_branch(r.fragment.text, serial);
  return r;
}

struct GridJobTimes {
  double total_ms = 0, render_ms = 0, readback_ms = 0;
};

inline GridJobTimes run_grid_job(const render::RenderRequest& request, const scene::Mesh& mesh) {
  const auto start = std::chrono::steady_clock::now();
  image::GridPngEncoder grid(image::GridLayout::for_frames(request.frames, request.width, request.height), request.frames);
  auto report = renderer().render(request, mesh, [&](int k, const image::Image& f, bool opaque) { grid.add_frame(k, f, opaque); });
  auto png = report ? grid.finish() : Expected<std::vector<std::uint8_t>>(report.error());
  if (!png) {
    std::fprintf(stderr, "the canonical job failed: %s\n", png.error().format().c_str());
    std::exit(1);
  }
  const double total = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return {total, report->times.render_ms, report->times.readback_ms};
}

}  // namespace shadelab::bench
