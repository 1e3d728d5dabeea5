// The canonical job (canonical_job.h: the course's bunny, `specular`, 9 frames 512 x 512, 4x MSAA,
// grid PNG) in a warm process,
// as a render worker runs it. Each iteration submits a shader the process has not seen (a unique
// constant), so compiling it is part of the time, as for a student's fresh submission.
//
// Counters are milliseconds per job: compile, first_frame, render (all frames), per_frame,
// readback, encode_tail (encode time left after the last frame: the encode overlaps rendering),
// and total. Run: build/bench/render_bench --benchmark_min_time=3
#include <benchmark/benchmark.h>

#include <chrono>
#include <iostream>
#include <optional>
#include <random>

#include "image/encode.h"
#include "image/grid.h"
#include "image/grid_png_encoder.h"
#include "image/metrics.h"
#include "bench_renderer.h"
#include "canonical_job.h"
#include "fresh_shader.h"
#include "render/renderer.h"

namespace {

using namespace shadelab;
using Clock = std::chrono::steady_clock;

using bench::renderer;

const scene::Mesh& bunny() { return bench::canonical_mesh(); }

render::RenderRequest canonical(int msaa, int serial) {
  render::RenderRequest r = bench::canonical_request();
  r.msaa = msaa;
  static const unsigned base = std::random_device{}() % 1000000u;  // unique to this process
  r.fragment.text = bench::with_fresh_branch(r.fragment.text, base * 1000u + static_cast<unsigned>(serial));
  return r;
}

enum class Output { none, grid_overlapped, grid_serial };

void run_job(benchmark::State& state, int msaa, Output output) {
  static int serial = 0;
  double compile = 0, first = 0, render_ms = 0, readback = 0, tail = 0, total = 0;
  for (auto _ : state) {
    const auto request = canonical(msaa, ++serial);
    const auto layout = image::GridLayout::for_frames(request.frames, request.width, request.height);
    const auto start = Clock::now();
    std::optional<image::GridPngEncoder> encoder;
    std::vector<image::Image> frames;
    if (output == Output::grid_overlapped) encoder.emplace(layout, request.frames);
    auto report = renderer().render(request, bunny(), [&](int k, const image::Image& f, bool opaque) {
      if (encoder) encoder->add_frame(k, f, opaque);
      if (output == Output::grid_serial) frames.push_back(f);
    });
    if (!report) {
      state.SkipWithError(report.error().format().c_str());
      return;
    }
    const auto rendered = Clock::now();
    if (encoder) benchmark::DoNotOptimize(encoder->finish());
    if (output == Output::grid_serial) benchmark::DoNotOptimize(image::encode_png(image::compose_grid(layout, frames)));
    const auto end = Clock::now();
    compile += report->times.compile_ms;
    first += report->times.first_frame_ms;
    render_ms += report->times.render_ms;
    readback += report->times.readback_ms;
    tail += std::chrono::duration<double, std::milli>(end - rendered).count();
    total += std::chrono::duration<double, std::milli>(end - start).count();
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["compile_ms"] = compile / n;
  state.counters["first_frame_ms"] = first / n;
  state.counters["render_ms"] = render_ms / n;
  state.counters["per_frame_ms"] = render_ms / n / bench::canonical_course().frames;
  state.counters["readback_ms"] = readback / n;
  state.counters["encode_tail_ms"] = tail / n;
  state.counters["total_ms"] = total / n;
}

// The submission's part of a specular grade: its frames under the homework's light and the probe
// light, 8-bit with 4x MSAA (as the canvas), with a count of the NaN and infinities in their colours.
// A fresh shader each time, so each iteration pays the compiles and JITs a student's grade pays.
//   census: what the grader draws: one pass for both lights, IEEE arithmetic, the census in it;
//   census_a_pass_each: the same a light at a time (what a `discard` gets);
//   float_pass: what it drew until stop 36: the 8-bit frames as compiled in one pass, then a
//     second pass into float targets with IEEE arithmetic, counted on the CPU.
enum class Lights { census, census_a_pass_each, float_pass };

std::vector<render::RenderRequest> under_grader_lights(const render::RenderRequest& base) {
  const auto& course = bench::canonical_course();
  const auto spec = course.grade_spec(*course.checkpoint("specular")->checkpoint, {});
  std::vector<render::RenderRequest> lit = {base};
  for (const auto& probe : spec.probes) {
    lit.push_back(base);
    for (const auto& s : grade::probe_settings(spec, probe)) lit.back().uniforms.push_back({s.name, s.value});
  }
  return lit;
}

void run_lights(benchmark::State& state, Lights how) {
  static int serial = 0;
  double frames = 0, nan = 0, passes = 0, ms = 0;
  const auto count_frame = [&](int, int, const image::Image& f, bool) {
    ++frames;
    if (f.type == image::PixelType::f32) nan += static_cast<double>(image::count_non_finite(f).nan);
  };
  const render::CensusSink census = [&](int, int, const image::NonFinite& n) { nan += static_cast<double>(n.nan); };
  for (auto _ : state) {
    auto base = canonical(4, ++serial);
    base.semantics = how == Lights::float_pass ? render::FloatSemantics::as_compiled : render::FloatSemantics::ieee;
    const auto lit = under_grader_lights(base);
    const auto start = Clock::now();
    Expected<render::RenderReport> report = render::RenderReport{};
    if (how == Lights::census) {
      report = renderer().render_together(lit, bunny(), count_frame, census);
      if (report) passes += report->passes;
    }
    for (size_t i = 0; how == Lights::census_a_pass_each && i < lit.size() && report; ++i) {
      report = renderer().render(lit[i], bunny(), [&](int k, const image::Image& f, bool o) { count_frame(0, k, f, o); }, census);
      if (report) passes += report->passes;
    }
    if (how == Lights::float_pass) {
      report = renderer().render_together(lit, bunny(), count_frame);
      auto as_float = lit;
      for (auto& r : as_float) r.pixel_type = image::PixelType::f32, r.msaa = 0, r.semantics = render::FloatSemantics::ieee;
      if (report) passes += report->passes, report = renderer().render_together(as_float, bunny(), count_frame);
      if (report) passes += report->passes;
    }
    if (!report) {
      state.SkipWithError(report.error().format().c_str());
      return;
    }
    ms += std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["frames"] = frames / n;  // 8-bit and float frames read back
  // Passes over the geometry: 1 for the census, 2 for the float pass, 2 a pass each. A shader the
  // rewrite declines is drawn a pass each, and this says so.
  state.counters["passes"] = passes / n;
  state.counters["nan"] = nan / n;  // 0: the course's shader
  state.counters["ms"] = ms / n;
}

void BM_GraderLights_Census(benchmark::State& s) { run_lights(s, Lights::census); }
void BM_GraderLights_CensusAPassEach(benchmark::State& s) { run_lights(s, Lights::census_a_pass_each); }
void BM_GraderLights_FloatPass(benchmark::State& s) { run_lights(s, Lights::float_pass); }

void BM_CanonicalJob_GridOverlapped(benchmark::State& s) { run_job(s, 4, Output::grid_overlapped); }
void BM_CanonicalJob_GridSerial(benchmark::State& s) { run_job(s, 4, Output::grid_serial); }
void BM_RenderOnly_Msaa4(benchmark::State& s) { run_job(s, 4, Output::none); }
void BM_RenderOnly_NoMsaa(benchmark::State& s) { run_job(s, 0, Output::none); }

// The grid encode alone, for the PNG settings table in docs/performance-log.md.
void BM_GridEncode(benchmark::State& state) {
  const auto request = canonical(4, 0);
  const auto layout = image::GridLayout::for_frames(request.frames, request.width, request.height);
  std::vector<image::Image> frames;
  (void)renderer().render(request, bunny(), [&](int, const image::Image& f, bool) { frames.push_back(f); });
  image::Image grid = image::compose_grid(layout, frames);
  const int level = static_cast<int>(state.range(0));
  const auto filter = static_cast<image::PngFilter>(state.range(1));
  const bool rgba = state.range(2) != 0;
  if (rgba) grid.bytes[3] = 254;  // one non-opaque pixel forces RGBA
  size_t bytes = 0;
  for (auto _ : state) {
    auto png = image::encode_png(grid, {.compression_level = level, .filter = filter, .threads = static_cast<int>(state.range(3))});
    bytes = png->size();
  }
  state.counters["bytes"] = static_cast<double>(bytes);
}

}  // namespace

BENCHMARK(BM_CanonicalJob_GridOverlapped)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_CanonicalJob_GridSerial)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_RenderOnly_Msaa4)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_RenderOnly_NoMsaa)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_GraderLights_Census)->Unit(benchmark::kMillisecond)->MinTime(4.0);
BENCHMARK(BM_GraderLights_CensusAPassEach)->Unit(benchmark::kMillisecond)->MinTime(4.0);
BENCHMARK(BM_GraderLights_FloatPass)->Unit(benchmark::kMillisecond)->MinTime(4.0);
// {zlib level, filter (0 none, 1 sub, 2 up), force RGBA, threads (0: one per core)}
BENCHMARK(BM_GridEncode)
    ->Args({6, 2, 1, 1})
    ->Args({1, 1, 1, 1})
    ->Args({1, 1, 0, 1})
    ->Args({1, 0, 0, 1})
    ->Args({1, 2, 0, 1})
    ->Args({1, 2, 0, 0})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);

BENCHMARK_MAIN();
