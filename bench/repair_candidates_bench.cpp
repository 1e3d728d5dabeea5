// What a repair search decides before any render (repair/repair_candidates.h): a class batch's
// second search for a student who writes the specular checkpoint as a tutorial does (`lightDir`,
// `reflectDir`) with the half vector for R, beside the course's reference and classmates who
// pass. The singles (the class's edits first, then the student's own and the reference's), and
// whether the class offers any edit at all (what a batch asks before it searches a second time).
// No GL: the edits are read from the programs' tokens. Run: build/bench/repair_candidates_bench
#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>
#include <vector>

#include "course/course_reader.h"
#include "repair/repair_candidates.h"
#include "road/repair_search.h"
#include "shader/shader_source.h"
#include "support/tutorial_program.h"

namespace {

using namespace shadelab;

std::string typed(std::string text, const std::string& find, const std::string& replace) {
  return text.replace(text.find(find), find.size(), replace);
}

// The student's program beside the reference and `classmates` distinct passing programs (the
// tutorial's, each with its own spacing: programs alike to the byte count once).
repair::RepairProgram tutorial_class(int classmates) {
  const course::Preset& specular = *course::builtin_course().preset("specular");
  const std::string reference = shader::unwrap(specular.fragment, shader::Stage::fragment)->glsl;
  const std::string tutorial = testkit::with_tutorial_main(reference);
  std::vector<repair::PassingProgram> class_programs;
  for (int k = 0; k < classmates; ++k)
    class_programs.push_back({specular.vertex, {"classmate.glsl", typed(tutorial, "    fragColor", std::string(k + 1, ' ') + "    fragColor")}});
  static const shader::ShaderFile student{"phong_frag.glsl", typed(tutorial, "reflect(-lightDir, norm)", "normalize(lightDir + viewDir)")};
  return repair::repair_program(specular.vertex, student, specular.vertex, specular.fragment, class_programs).value();
}

void BM_SingleCandidates(benchmark::State& state) {
  const auto program = tutorial_class(static_cast<int>(state.range(0)));
  const repair::CandidateCounts counts = road::RepairBudget{}.candidate_counts();
  size_t made = 0, from_class = 0;
  for (auto _ : state) {
    const auto singles = repair::single_candidates(program, counts);
    made = singles.size();
    from_class = static_cast<size_t>(std::count_if(singles.begin(), singles.end(), [](const auto& c) { return c.from_class; }));
  }
  state.counters["singles"] = static_cast<double>(made);
  state.counters["from_class"] = static_cast<double>(from_class);
}

void BM_ClassEdits(benchmark::State& state) {
  const auto program = tutorial_class(static_cast<int>(state.range(0)));
  const repair::CandidateCounts counts = road::RepairBudget{}.candidate_counts();
  size_t offered = 0;
  for (auto _ : state) offered = repair::class_edits(program, counts).size();
  state.counters["offered"] = static_cast<double>(offered);
}

}  // namespace

BENCHMARK(BM_SingleCandidates)->Arg(0)->Arg(3)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_ClassEdits)->Arg(3)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_MAIN();
