// How the canonical job's time grows with the mesh and the frame: 9 frames of a UV sphere of
// ~10k, ~100k and ~1M triangles at the course's canvas and 2x and 4x it each way (512 x 512: 0.26, 1.0
// and 4.2 MPixel),
// the course's default preset and samples, the grid PNG encoded while the frames render, as a worker does.
// Each job compiles a fragment shader the process has not seen (a never-taken branch on a new
// constant), so every cell pays a fresh JIT as a student's submission does.
//
// Prints one table row per cell: the job's median over JOBS runs, its render phase, and the
// time per frame; then the marginal costs per million triangles and per MPixel fitted from the
// cells (least squares on per-frame time = a + b * triangles + c * pixels) and each cell's
// residual against that fit, so "linear in triangles and pixels" is a number, not a look.
//
//   build/bench/scale_bench [JOBS=3]
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "grid_job.h"
#include "scene/uv_sphere.h"
#include "stats.h"

namespace {

using namespace shadelab;

struct Cell {
  size_t triangles = 0;
  int width = 0, height = 0;
  double job_ms = 0, render_ms = 0;
  double per_frame() const { return job_ms / bench::canonical_course().frames; }
  double mpixels() const { return static_cast<double>(width) * height / 1e6; }
};

Cell measure(const scene::Mesh& mesh, int width, int height, int jobs) {
  static unsigned serial = std::random_device{}() % 100000000u;
  std::vector<double> totals, renders;
  for (int j = 0; j < jobs; ++j) {
    const auto t = bench::run_grid_job(bench::fresh_canonical(++serial, width, height), mesh);
    totals.push_back(t.total_ms);
    renders.push_back(t.render_ms);
  }
  return {mesh.triangle_count(), width, height, bench::median(totals), bench::median(renders)};
}

// Least squares for y = a + b * x1 + c * x2 (normal equations, 3 x 3, Cramer's rule).
std::array<double, 3> fit(const std::vector<Cell>& cells) {
  double m[3][3] = {}, v[3] = {};
  for (const auto& c : cells) {
    const double x[3] = {1.0, static_cast<double>(c.triangles) / 1e6, c.mpixels()};
    for (int i = 0; i < 3; ++i) {
      v[i] += x[i] * c.per_frame();
      for (int k = 0; k < 3; ++k) m[i][k] += x[i] * x[k];
    }
  }
  const auto det = [](const double a[3][3]) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const double d = det(m);
  std::array<double, 3> out{};
  for (int col = 0; col < 3; ++col) {
    double r[3][3];
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) r[i][k] = k == col ? v[i] : m[i][k];
    out[static_cast<size_t>(col)] = det(r) / d;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const int jobs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const std::array<int, 3> segments = {100, 316, 1000};  // a UV sphere has segments^2 triangles
  // The course's canvas, and 2x and 4x it each way.
  const auto& course = bench::canonical_course();
  const std::array<std::array<int, 2>, 3> sizes = {
      {{course.width, course.height}, {2 * course.width, 2 * course.height}, {4 * course.width, 4 * course.height}}};
  std::vector<Cell> cells;
  std::printf("| triangles | frame | MPixel | job ms (median of %d) | render ms | ms per frame |\n| --- | --- | --- | --- | --- | --- |\n", jobs);
  for (int s : segments) {
    scene::Mesh mesh = scene::uv_sphere(1.0, {0, 0, 0}, s);
    scene::fit_to(mesh, scene::bounds(bench::canonical_mesh()));
    for (const auto& [w, h] : sizes) {
      const Cell c = measure(mesh, w, h, jobs);
      cells.push_back(c);
      std::printf("| %zu | %d x %d | %.1f | %.0f | %.0f | %.1f |\n", c.triangles, w, h, c.mpixels(), c.job_ms, c.render_ms, c.per_frame());
      std::fflush(stdout);
    }
  }
  const auto [a, b, c] = fit(cells);
  std::printf("\nper frame ~ %.2f ms + %.2f ms per million triangles + %.2f ms per MPixel\n", a, b, c);
  double worst = 0;
  for (const auto& cell : cells) {
    const double predicted = a + b * static_cast<double>(cell.triangles) / 1e6 + c * cell.mpixels();
    worst = std::max(worst, std::abs(cell.per_frame() - predicted) / cell.per_frame());
  }
  std::printf("largest residual against that fit: %.0f%% of a cell's time\n", 100 * worst);
  return 0;
}
