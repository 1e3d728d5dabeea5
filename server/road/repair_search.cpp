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

// What one pass of the search came to.
enum class Pass { confirmed, budget_spent, none_passed, trouble };

// Whether the search goes on after a pass: nothing confirmed, and the service could run it.
bool open(Pass p) { return p == Pass::none_passed || p == Pass::budget_spent; }

// The singles in two groups, each in the singles' order: first those that align the student's line
// with the reference (repair::aligns) or edit a line where the values say a value first departs
// from the reference's (repair/value_probes.h), then the others. A departure alone does not put an
// edit first: where the student clamps at the write and the reference at the use (`float diff =
// dot(N, L)` against `max(0.0, NdotL)`), the value departs at the use, a line after the mistake.
struct Singles {
  std::vector<repair::RepairCandidate> first, rest;
  std::vector<repair::RepairCandidate> all() const {
    std::vector<repair::RepairCandidate> out = first;
    out.insert(out.end(), rest.begin(), rest.end());
    return out;
  }
};

bool at(const repair::RepairEdit& e, const std::set<int>& departing) { return e.stage == shader::Stage::fragment && departing.count(e.line) > 0; }

Singles split_at(std::vector<repair::RepairCandidate> singles, const std::set<int>& departing) {
  Singles out;
  for (auto& c : singles) {
    const bool first = std::any_of(c.edits.begin(), c.edits.end(), [&](const auto& e) { return repair::aligns(e) || at(e, departing); });
    (first ? out.first : out.rest).push_back(std::move(c));
  }
  return out;
}

// The pairs of two of `first` (screened: `distances`) at two lines where a value departs, in
// repair::pair_candidates' order: two mistakes whose values do not depend on each other, each
// found at its own line.
std::vector<repair::RepairCandidate> departure_pairs(const repair::RepairProgram& p, const std::vector<repair::RepairCandidate>& first,
                                                     const std::vector<double>& distances, double own, const std::set<int>& departing,
                                                     const repair::CandidateCounts& counts) {
  auto pairs = repair::pair_candidates(p, first, distances, own, counts);
  std::erase_if(pairs, [&](const repair::RepairCandidate& c) {
    return c.edits.size() != 2 || !at(c.edits[0], departing) || !at(c.edits[1], departing) || c.edits[0].line == c.edits[1].line;
  });
  return pairs;
}

// The screened single that drew nearest the reference, nearer than the student's `own` program
// (the first of equals); none where none did.
std::optional<size_t> nearest(const std::vector<double>& distances, double own) {
  std::optional<size_t> out;
  for (size_t i = 0; i < distances.size(); ++i)
    if (distances[i] < own && (!out || distances[i] < distances[*out])) out = i;
  return out;
}

// Whether `c`'s program is one of `tried`'s.
bool tried(const repair::RepairCandidate& c, const std::vector<repair::RepairCandidate>& tried) {
  return std::any_of(tried.begin(), tried.end(), [&](const auto& t) { return t.vertex.text == c.vertex.text && t.fragment.text == c.fragment.text; });
}

// The search's state: what it was given and what it has spent.
struct Search {
  worker::WorkerPool& pool;
  const worker::Job& failed;
  const std::string& mesh;
  const RepairBudget& budget;
  grade::Report& report;
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

  // try_in_order within what is `left` of a budget of confirmations, which it spends.
  Pass try_within(const std::vector<repair::RepairCandidate>& candidates, int& left, std::vector<double>* distances,
                  const repair::RepairCandidate** winner) {
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

  // The values `c`'s program computes beside the reference's, read on the screening canvas
  // (grade/value_reading.h); none where the service could not run it.
  std::optional<repair::ValueAgreement> values_of(const repair::RepairCandidate& c) {
    worker::Job job = candidate_job(failed, c, budget, &probes);
    job.grade.read_values = true;
    auto submitted = submit_when_room(pool, worker::to_message(job, mesh));
    if (!submitted) return std::nullopt;
    worker::JobResult done = submitted->get();
    if (!done.answered) return std::nullopt;
    auto result = worker::result_from<worker::GradeResult>(done.answer);
    if (!result || !result->values) return std::nullopt;
    return std::move(*result->values);
  }

  // The student's own program's distance on the screening canvas: what a single edit must improve
  // on to be one of a pair.
  std::optional<double> own_distance(const repair::RepairProgram& p) {
    auto own = grade_candidates(pool, {candidate_job(failed, repair::candidate_of(p, {}), budget, &probes)}, mesh);
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
  Search search{pool, failed, mesh_bytes, budget, report};
  const repair::CandidateCounts counts = budget.candidate_counts();
  const std::set<int> departing = repair::departing_lines(program->read, values);
  const Singles singles = split_at(repair::single_candidates(*program, counts), departing);
  std::vector<double> distances;  // each screened single's, `singles.first`'s first
  std::vector<repair::RepairCandidate> early, next, pairs;
  const repair::RepairCandidate* winner = nullptr;  // in `singles`, `early`, `next` or `pairs`
  int singles_left = budget.confirmations, pairs_left = budget.pair_confirmations;
  const bool pairing = budget.pairs > 0;
  std::optional<double> own;
  const Pass first = search.try_within(singles.first, singles_left, &distances, &winner);
  Pass pass = first;
  // Two lines where a value departs: a mistake at each, paired before any other single is screened.
  if (open(pass) && pairing && pairs_left > 0 && departing.size() >= 2) {
    if (!(own = search.own_distance(*program))) return;
    early = departure_pairs(*program, singles.first, distances, *own, departing, counts);
    pass = search.try_within(early, pairs_left, nullptr, &winner);
    if (open(pass)) pass = first;
  }
  // The single of those screened that drew nearest: where its program's values still depart is
  // where a second mistake is, which the first one's error hid from the student's values.
  if (open(pass) && pairing && pairs_left > 0 && values.read) {
    if (!own && !(own = search.own_distance(*program))) return;
    if (const auto n = nearest(distances, *own)) {
      const auto& single = singles.first[*n];
      if (const auto read = search.values_of(single)) {
        repair::CandidateCounts left = counts;
        left.pairs -= static_cast<int>(early.size());  // `pairs` in all
        next = repair::pairs_with(*program, single.edits.front(), singles.all(), repair::departing_after(*program, single, *read), left);
        std::erase_if(next, [&](const auto& c) { return tried(c, early); });
        const Pass after = search.try_within(next, pairs_left, nullptr, &winner);
        pass = open(after) ? first : after;
      }
    }
  }
  if (pass == Pass::none_passed) pass = search.try_within(singles.rest, singles_left, &distances, &winner);
  // A single whose screen passed and whose full render did not is a mistake half mended: the
  // pairs still get confirmations of their own.
  if (open(pass) && pairing && pairs_left > 0) {
    // No one edit repairs it: two edits (repair::pair_candidates says which, in what order).
    if (!own && !(own = search.own_distance(*program))) return;
    pairs = repair::pair_candidates(*program, singles.all(), distances, *own, counts);
    std::erase_if(pairs, [&](const repair::RepairCandidate& c) { return tried(c, early) || tried(c, next); });
    pairs.resize(std::min(pairs.size(), static_cast<size_t>(std::max(0, budget.pairs - static_cast<int>(early.size() + next.size())))));  // `pairs` in all
    pass = search.try_within(pairs, pairs_left, nullptr, &winner);
  }
  if (pass == Pass::trouble) return;
  search.spent.budget_spent = pass != Pass::confirmed;
  report.repair_search = std::move(search.spent);
  if (winner)
    grade::state_repair(repair::said_repair(*program, winner->edits, shown, vectors), failed.grade.starter_constants,
                        program->fragment.file->text, report);
}

}  // namespace shadelab::road
