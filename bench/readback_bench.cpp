// Direct reads against pixel buffers (gl::Readback) on the canonical job (canonical_job.h, the grid
// PNG encoded while the frames render, as a worker does), in
// one process, the two modes alternating job by job, each job a fragment shader not seen before.
// Prints each mode's p50 (job and readback) and the median of the pairs' ratios: what
// `gl::Readback`'s default per device rests on.
//
//   build/bench/readback_bench [PAIRS=20]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "grid_job.h"
#include "stats.h"

using namespace shadelab;
using bench::median;

int main(int argc, char** argv) {
  const int pairs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 20;
  const scene::Mesh* bunny = &bench::canonical_mesh();
  unsigned serial = std::random_device{}() % 100000000u;
  const auto one_job = [&](gl::Readback mode) {
    bench::renderer().set_readback(mode);
    return bench::run_grid_job(bench::fresh_canonical(serial++), *bunny);
  };
  for (auto mode : {gl::Readback::direct, gl::Readback::pixel_buffer}) one_job(mode);  // warm both paths
  std::vector<double> direct, buffered, direct_read, buffered_read, ratios;
  for (int i = 0; i < pairs; ++i) {
    const bool direct_first = i % 2 == 0;
    const auto a = one_job(direct_first ? gl::Readback::direct : gl::Readback::pixel_buffer);
    const auto b = one_job(direct_first ? gl::Readback::pixel_buffer : gl::Readback::direct);
    const auto& d = direct_first ? a : b;
    const auto& p = direct_first ? b : a;
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
