// The floor alone (bench/floor_job.h says what it is): per-phase means and the p50 of the job.
// Each job compiles a fragment shader the process has never seen.
//
//   build/bench/floor_bench [JOBS=20]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "floor_job.h"

int main(int argc, char** argv) {
  const int jobs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 20;
  shadelab::bench::FloorJob floor;
  const unsigned base = std::random_device{}() % 100000000u;
  std::vector<shadelab::bench::FloorPhases> runs;
  for (int i = -2; i < jobs; ++i) {  // two warm-up jobs: the context's first draws, the vertex shader's JIT
    const auto p = floor.run(base + static_cast<unsigned>(i + 2));
    if (i >= 0) runs.push_back(p);
  }
  shadelab::bench::FloorPhases mean;
  std::vector<double> totals;
  for (const auto& p : runs) {
    mean.compile += p.compile / jobs;
    mean.render += p.render / jobs;
    mean.readback += p.readback / jobs;
    mean.encode += p.encode / jobs;
    totals.push_back(p.total);
  }
  std::sort(totals.begin(), totals.end());
  std::printf("floor (raw EGL + GLES + libpng, serial), %d jobs: p50 %.1f ms; mean compile %.1f, render %.1f, readback %.1f, encode %.1f\n",
              jobs, totals[totals.size() / 2], mean.compile, mean.render, mean.readback, mean.encode);
  return 0;
}
