// What WebGL 2's shader rules add to a compile (issue 17's "/api/compile well under 10 ms per
// pair"): the rules alone (glslang parses each stage twice: the AST, then the preprocessor pass),
// and the renderer's whole compile and link on the real driver, each iteration a shader the
// process has not seen (a unique constant), for the homework's specular pair and an ES 1.00 twin.
// Run: build/bench/webgl_rules_bench
#include <benchmark/benchmark.h>

#include <iostream>

#include "canonical_job.h"
#include "bench_renderer.h"
#include "render/renderer.h"
#include "shader/webgl_rules.h"

namespace {

using namespace shadelab;

using bench::renderer;

// The specular fragment shader with a constant no earlier iteration used: a real code change.
shader::ShaderFile fresh_fragment(const course::Preset& p, long k) {
  shader::ShaderFile f = p.fragment;
  const std::string marker = "void main";
  f.text.insert(f.text.find(marker), "const float kChange = " + std::to_string(k) + ".0;\n");
  return f;
}

void BM_WebglRulesOnly(benchmark::State& state) {
  const auto& p = bench::canonical_preset();
  long k = 0;
  for (auto _ : state) {
    auto vertex = shader::unwrap(p.vertex, shader::Stage::vertex);
    auto fragment = shader::unwrap(fresh_fragment(p, ++k), shader::Stage::fragment);
    auto checked = shader::apply_webgl_rules(*vertex, *fragment, p.vertex, p.fragment);
    if (!checked) state.SkipWithError(checked.error().format().c_str());
    benchmark::DoNotOptimize(checked);
  }
}

// The same with an `#extension` directive first, as a student who copied one in writes it: the
// stage is preprocessed once more to find whether any code stands before the directive.
void BM_WebglRulesWithAnExtension(benchmark::State& state) {
  const auto& p = bench::canonical_preset();
  long k = 2'000'000;
  for (auto _ : state) {
    auto vertex = shader::unwrap(p.vertex, shader::Stage::vertex);
    shader::ShaderFile f = fresh_fragment(p, ++k);
    const size_t version_end = f.text.find('\n', f.text.find("#version 300 es"));
    f.text.insert(version_end + 1, "#extension all : warn\n");
    auto fragment = shader::unwrap(f, shader::Stage::fragment);
    auto checked = shader::apply_webgl_rules(*vertex, *fragment, p.vertex, f);
    if (!checked) state.SkipWithError(checked.error().format().c_str());
    benchmark::DoNotOptimize(checked);
  }
}

void BM_CompileAndLink(benchmark::State& state) {
  const auto& p = bench::canonical_preset();
  long k = 1'000'000;
  for (auto _ : state) {
    auto report = renderer().compile(p.vertex, fresh_fragment(p, ++k));
    if (!report) state.SkipWithError(report.error().format().c_str());
    benchmark::DoNotOptimize(report);
  }
}

}  // namespace

BENCHMARK(BM_WebglRulesOnly)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_WebglRulesWithAnExtension)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_CompileAndLink)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_MAIN();
