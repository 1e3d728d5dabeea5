#include "road/repair_search.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <optional>
#include <set>
#include <thread>
#include <vector>

#include "grade/diagnosis.h"
#include "grade/repair_statement.h"
#include "repair/said_repair.h"
#include "repair/search_order.h"
#include "worker/result.h"

namespace shadelab::road {

namespace {

constexpr int kScreenFrames = 3;

// The program `job` draws, read beside its reference and the class's passing programs.
Expected<repair::RepairProgram> program_of(const worker::Job& job, const std::vector<repair::PassingProgram>& classmates) {
  return repair::repair_program(job.request.vertex, job.request.fragment, job.grade.reference_vertex, job.grade.reference_fragment,
                               classmates);
}

// The probe lights a screen draws under: none where the student's frames fail under the page's
// light (it alone filters), else those under which they fail: a program right under the page's
// light and wrong under a probe would pass every screen, and each pass spend a confirmation.
std::vector<std::string> screen_probes(const grade::Report& failed) {
  std::vector<std::string> out;
  for (const auto& f : failed.frames) {
    if (f.grade.pass) continue;
    if (f.light == "homework") return {};
    if (std::find(out.begin(), out.end(), f.light) == out.end()) out.push_back(f.light);
  }
  return out;
}

// The grade's job for a candidate: a verdict only (no catalogue, no formula, no heat map), on the
// grade's canvas or, to screen (`screen`: the probes it keeps), one `budget.screen_size` on its
// longer side within its share of the deadlines.
worker::Job candidate_job(const worker::Job& failed, const repair::RepairCandidate& c, const RepairBudget& budget,
                          const std::vector<std::string>* screen) {
  worker::Job job = failed;
  job.request.vertex = c.vertex;
  job.request.fragment = c.fragment;
  job.grade.mistakes.clear();
  job.grade.formula.reset();
  job.grade.starter_constants.clear();
  job.grade.heatmap = grade::HeatMap::never;
  if (screen) {
    // Three frames a third of a turn apart, under the page's light (or the probes the student's
    // frames fail under): a filter. Only the confirming render, every frame and light the grade
    // draws, states a repair.
    job.request.degrees_per_frame *= static_cast<double>(job.request.frames) / kScreenFrames;
    job.request.frames = kScreenFrames;
    std::erase_if(job.grade.probes, [&](const grade::Probe& p) { return std::find(screen->begin(), screen->end(), p.name) == screen->end(); });
    const double scale = static_cast<double>(budget.screen_size) / std::max(job.request.width, job.request.height);
    job.request.width = std::max(1, static_cast<int>(std::lround(job.request.width * scale)));
    job.request.height = std::max(1, static_cast<int>(std::lround(job.request.height * scale)));
    job.grade.reference_store = {};  // a screening canvas's references are not worth keeping
    job.deadline_share = budget.screen_deadline_share;
  }
  return job;
}

// A busy queue delays a candidate, never drops it: the answer must not depend on the load. Only a
// queue that stays full for as long as a worker's start may take is the service's trouble.
Expected<std::future<worker::JobResult>> submit_when_room(worker::WorkerPool& pool, const worker::Message& job) {
  const auto give_up = std::chrono::steady_clock::now() + pool.config().start_deadline;
  for (;;) {
    auto submitted = pool.submit(job);
    if (submitted || submitted.error().code != ErrorCode::queue_full || std::chrono::steady_clock::now() > give_up) return submitted;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

// A candidate's grade: whether it passed, and how far its frames are from the reference's: the
// mean RMS difference (0 to 1), continuous so that an edit that mends one mistake of two counts
// as nearer, in steps of 1/10000 so that a GPU's last bits do not reorder candidates (1 where
// nothing was drawn or a frame holds NaN).
struct Graded {
  bool pass = false;
  double distance = 1.0;
};

double distance_of(const grade::Report& report) {
  if (report.frames.empty()) return 1.0;
  double sum = 0;
  for (const auto& f : report.frames) sum += f.grade.non_finite.nan + f.grade.non_finite.inf > 0 ? 1.0 : f.grade.metrics.rmse;
  return std::round(10000.0 * sum / static_cast<double>(report.frames.size())) / 10000.0;
}

// Each candidate's grade; an Error when the service could not run one (a candidate's own failure,
// its compile, a hang, a crash, is a failing grade, not an Error).
Expected<std::vector<Graded>> grade_candidates(worker::WorkerPool& pool, const std::vector<worker::Job>& jobs, const std::string& mesh) {
  std::vector<std::future<worker::JobResult>> running;
  for (const auto& job : jobs) {
    auto submitted = submit_when_room(pool, worker::to_message(job, mesh));
    if (!submitted) return submitted.take_error();
    running.push_back(std::move(*submitted));
  }
  std::vector<Graded> out;
  std::optional<Error> trouble;
  for (auto& f : running) {
    worker::JobResult done = f.get();
    if (!done.answered) {
      if (!info(done.error.code).submission_caused) trouble = done.error;
      out.push_back({});
      continue;
    }
    auto result = worker::result_from<worker::GradeResult>(done.answer);
    if (!result) return result.take_error();
    out.push_back({result->report.pass, distance_of(result->report)});
  }
  if (trouble) return *trouble;
  return out;
}

using repair::Pass;

// The search's screens drawn on the service's workers: what it was given and what it has spent.
struct WorkerScreens final : repair::Screens {
  WorkerScreens(worker::WorkerPool& on, const worker::Job& job, const std::string& mesh_bytes, const RepairBudget& within,
                grade::Report& into, const repair::RepairProgram& read)
      : pool(on), failed(job), mesh(mesh_bytes), budget(within), report(into), program(read) {}

  worker::WorkerPool& pool;
  const worker::Job& failed;
  const std::string& mesh;
  const RepairBudget& budget;
  grade::Report& report;
  const repair::RepairProgram& program;
  const std::vector<std::string> probes = screen_probes(report);  // the screens'
  grade::RepairSearch spent;

  // Screens `candidates` in order, a wave at a time (the machine's speed, never the answer), reads
  // their verdicts in order and renders each screened pass again at the grade's frames until one
  // is confirmed (`winner`) or the confirmations are spent. `distances`: each screen's distance.
  // The first wave is the smallest candidate alone: it is most often the repair (a median of one
  // candidate), and a wave's others would be screened for nothing, a class's workers' time.
  Pass try_in_order(const std::vector<repair::RepairCandidate>& candidates, int confirmations, std::vector<double>* distances,
                    const repair::RepairCandidate** winner) {
    const int confirmed_before = spent.confirmations;
    const size_t width = static_cast<size_t>(std::max({1, budget.wave, pool.config().workers}));
    for (size_t first = 0, wave = 1; first < candidates.size(); first += wave, wave = width) {
      const size_t last = std::min(candidates.size(), first + wave);
      std::vector<worker::Job> screens;
      for (size_t i = first; i < last; ++i) screens.push_back(candidate_job(failed, candidates[i], budget, &probes));
      auto screened = grade_candidates(pool, screens, mesh);
      if (!screened) return could_not_run(screened.error());
      for (size_t i = first; i < last; ++i) {
        ++spent.candidates;
        const Graded& g = (*screened)[i - first];
        if (distances) distances->push_back(g.distance);
        if (!g.pass) continue;
        ++spent.confirmations;
        auto confirmed = grade_candidates(pool, {candidate_job(failed, candidates[i], budget, nullptr)}, mesh);
        if (!confirmed) return could_not_run(confirmed.error());
        if (confirmed->front().pass) {
          *winner = &candidates[i];
          return Pass::confirmed;
        }
        if (spent.confirmations - confirmed_before == confirmations) return Pass::budget_spent;
      }
    }
    return Pass::none_passed;
  }

  Pass try_within(const std::vector<repair::RepairCandidate>& candidates, int& left, std::vector<double>* distances,
                  const repair::RepairCandidate** winner) override {
    if (left < 1) return Pass::budget_spent;
    const int before = spent.confirmations;
    const Pass p = try_in_order(candidates, left, distances, winner);
    left -= spent.confirmations - before;
    return p;
  }

  Pass could_not_run(const Error& e) {
    report.warnings.push_back("the repair search could not run (" + e.message + ")");
    return Pass::trouble;
  }

  // Read on the screening canvas, within the grade's whole deadlines, as the student's own values
  // were: a screen's share would drop the values where the machine is slower, and the answer
  // would then depend on the machine.
  std::optional<repair::ValueAgreement> values_of(const repair::RepairCandidate& c) override {
    worker::Job job = candidate_job(failed, c, budget, &probes);
    job.deadline_share = failed.deadline_share;
    job.grade.read_values = true;
    ++spent.values_read;
    auto submitted = submit_when_room(pool, worker::to_message(job, mesh));
    if (!submitted) return std::nullopt;
    worker::JobResult done = submitted->get();
    if (!done.answered) return std::nullopt;
    auto result = worker::result_from<worker::GradeResult>(done.answer);
    if (!result || !result->values) return std::nullopt;
    return std::move(*result->values);
  }

  // What a single edit must improve on to be one of a pair.
  std::optional<double> own_distance() override {
    auto own = grade_candidates(pool, {candidate_job(failed, repair::candidate_of(program, {}), budget, &probes)}, mesh);
    if (!own) {
      could_not_run(own.error());
      return std::nullopt;
    }
    return own->front().distance;
  }
};

}  // namespace

bool class_offers_edits(const worker::Job& failed, const std::vector<repair::PassingProgram>& classmates, const RepairBudget& budget) {
  const auto program = program_of(failed, classmates);
  return program && !repair::class_edits(*program, budget.candidate_counts()).empty();
}

bool wants_repair(const grade::Report& report, const std::vector<grade::StarterConstant>& constants) {
  if (report.pass || report.frames.empty() || !report.diagnostics.empty()) return false;
  if (report.explanation && report.explanation->explained) return false;
  const auto changed = [&](const grade::StarterConstant& c) { return report.diagnosis == grade::changed_constant_diagnosis(c.variable); };
  // The grader's own swapped channels say what, never where: the search finds the line.
  return report.diagnosis.empty() || report.diagnosis == grade::to_string(grade::Diagnosis::nan) ||
         report.diagnosis == grade::to_string(grade::Diagnosis::swapped_channels) || std::any_of(constants.begin(), constants.end(), changed);
}

void search_repair(worker::WorkerPool& pool, const worker::Job& failed, const std::string& mesh_bytes, repair::RepairShown shown,
                   const grade::VectorWords& vectors, grade::Report& report, const RepairBudget& budget,
                   const std::vector<repair::PassingProgram>& classmates, const repair::ValueAgreement& values) {
  const auto program = program_of(failed, classmates);
  if (!program) {
    // A program the search cannot read gets no search: a stage beyond its budget says why.
    if (program.error().code == ErrorCode::payload_too_large) report.warnings.push_back("no repair was searched for: " + program.error().message);
    return;
  }
  if (budget.confirmations < 1) return;  // nothing screened could be stated
  WorkerScreens screens{pool, failed, mesh_bytes, budget, report, *program};
  const auto outcome = repair::search_in_order(*program, budget.candidate_counts(), {budget.confirmations, budget.pair_confirmations}, values, screens);
  if (outcome.pass == Pass::trouble) return;
  screens.spent.budget_spent = outcome.pass != Pass::confirmed;
  report.repair_search = std::move(screens.spent);
  if (!outcome.edits.empty())
    grade::state_repair(repair::said_repair(*program, outcome.edits, shown, vectors, values), failed.grade.starter_constants,
                        program->fragment.file->text, report);
}

}  // namespace shadelab::road
