#include "road/repair_search.h"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <future>
#include <thread>
#include <optional>
#include <vector>

#include "grade/diagnosis.h"
#include "worker/result.h"

namespace shadelab::road {

namespace {

constexpr int kScreenFrames = 3;

// One stage of the student's program as the driver gets it, and the file it came from.
struct StudentStage {
  const shader::ShaderFile* file = nullptr;
  shader::UnwrappedSource source;
};

struct Candidate {
  grade::RepairEdit edit;
  shader::ShaderFile vertex, fragment;  // the program with the edit made
};

struct Program {
  StudentStage vertex, fragment;
  const StudentStage& operator[](shader::Stage s) const { return s == shader::Stage::vertex ? vertex : fragment; }
};

std::optional<Program> program_of(const worker::Job& job) {
  auto vertex = shader::unwrap(job.request.vertex, shader::Stage::vertex);
  auto fragment = shader::unwrap(job.request.fragment, shader::Stage::fragment);
  if (!vertex || !fragment) return std::nullopt;
  return Program{{&job.request.vertex, std::move(*vertex)}, {&job.request.fragment, std::move(*fragment)}};
}

// The budget's candidates, smallest first: the edited stage given as the GLSL the edit made (the
// same program the driver compiles), the other as the student's file.
std::vector<Candidate> candidates(const Program& p, int most) {
  std::vector<grade::RepairEdit> edits = grade::program_repair_edits(p.vertex.source.glsl, p.fragment.source.glsl);
  if (edits.size() > static_cast<size_t>(most)) edits.resize(most);
  std::vector<Candidate> out;
  for (auto& e : edits) {
    Candidate c{std::move(e), *p.vertex.file, *p.fragment.file};
    shader::ShaderFile& edited = c.edit.stage == shader::Stage::vertex ? c.vertex : c.fragment;
    edited.text = grade::with_edit(p[c.edit.stage].source.glsl, c.edit);
    out.push_back(std::move(c));
  }
  return out;
}

// The grade's job for a candidate: a verdict only (no catalogue, no formula, no heat map), on the
// grade's canvas or, to screen, one `budget.screen_size` on its longer side within its share of the deadlines.
worker::Job candidate_job(const worker::Job& failed, const Candidate& c, const RepairBudget& budget, bool screen) {
  worker::Job job = failed;
  job.request.vertex = c.vertex;
  job.request.fragment = c.fragment;
  job.grade.mistakes.clear();
  job.grade.formula.reset();
  job.grade.starter_constants.clear();
  job.grade.heatmap = grade::HeatMap::never;
  if (screen) {
    // Three frames a third of a turn apart, under the page's light alone: a filter. Only the
    // confirming render, every frame and light the grade draws, states a repair.
    job.request.degrees_per_frame *= static_cast<double>(job.request.frames) / kScreenFrames;
    job.request.frames = kScreenFrames;
    job.grade.probes.clear();
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

// Whether each candidate's grade passes; an Error when the service could not run one (a
// candidate's own failure, its compile, a hang, a crash, is a failing grade, not an Error).
Expected<std::vector<bool>> grade_candidates(worker::WorkerPool& pool, const std::vector<worker::Job>& jobs, const std::string& mesh) {
  std::vector<std::future<worker::JobResult>> running;
  for (const auto& job : jobs) {
    auto submitted = submit_when_room(pool, worker::to_message(job, mesh));
    if (!submitted) return submitted.take_error();
    running.push_back(std::move(*submitted));
  }
  std::vector<bool> passed;
  std::optional<Error> trouble;
  for (auto& f : running) {
    worker::JobResult done = f.get();
    if (!done.answered) {
      if (!info(done.error.code).submission_caused) trouble = done.error;
      passed.push_back(false);
      continue;
    }
    auto result = worker::result_from<worker::GradeResult>(done.answer);
    if (!result) return result.take_error();
    passed.push_back(result->report.pass);
  }
  if (trouble) return *trouble;
  return passed;
}

// The confirmed repair, said as far as `shown` allows: "phong_frag.js line 20: L is not normalised:
// ...", then, with the repaired line, "With `...` the frames match ...".
void state_repair(const Program& p, const Candidate& c, grade::RepairShown shown, grade::Report& report) {
  const StudentStage& stage = p[c.edit.stage];
  grade::Repair repair{c.edit.kind, std::nullopt, std::nullopt, grade::repair_words(c.edit), std::nullopt};
  std::vector<std::string> said = {repair.text + "."};
  if (shown != grade::RepairShown::what) {
    const int line = stage.source.locate(c.edit.line, 0).file_line;
    repair.file = stage.file->name;
    repair.line = line;
    said.front() = (stage.file->name.empty() ? std::string(to_string(c.edit.stage)) : stage.file->name) + " line " + std::to_string(line) + ": " +
                   repair.text + ".";
  }
  if (shown == grade::RepairShown::repaired_line) {
    repair.repaired_line = grade::edited_line(stage.source.glsl, c.edit);
    said.push_back("With `" + *repair.repaired_line + "` the frames match the reference's on every frame and light the grade draws.");
  }
  // The formula's "cannot say why" is superseded by what a render confirmed.
  auto& m = report.messages;
  if (report.explanation && !report.explanation->explained) m.erase(std::remove(m.begin(), m.end(), report.explanation->text), m.end());
  m.insert(m.begin() + std::min<size_t>(1, m.size()), said.begin(), said.end());
  report.repair_search->found = std::move(repair);
}

}  // namespace

bool wants_repair(const grade::Report& report) {
  if (report.pass || report.frames.empty() || !report.diagnostics.empty()) return false;
  if (report.explanation && report.explanation->explained) return false;
  return report.diagnosis.empty() || report.diagnosis == grade::to_string(grade::Diagnosis::nan);
}

void search_repair(worker::WorkerPool& pool, const worker::Job& failed, const std::string& mesh_bytes, grade::RepairShown shown,
                   grade::Report& report, const RepairBudget& budget) {
  const auto program = program_of(failed);
  if (!program || budget.confirmations < 1) return;  // nothing screened could be stated
  const std::vector<Candidate> all = candidates(*program, budget.candidates);
  grade::RepairSearch search;
  // A wave screens several candidates at once (the machine's speed), but the search reads their
  // verdicts in order, and counts only those it read: the same count on any machine.
  const size_t wave = static_cast<size_t>(std::max({1, budget.wave, pool.config().workers}));
  for (size_t first = 0; first < all.size(); first += wave) {
    const size_t last = std::min(all.size(), first + wave);
    std::vector<worker::Job> screens;
    for (size_t i = first; i < last; ++i) screens.push_back(candidate_job(failed, all[i], budget, true));
    auto screened = grade_candidates(pool, screens, mesh_bytes);
    if (!screened) {
      report.warnings.push_back("the repair search could not run (" + screened.error().message + ")");
      return;
    }
    for (size_t i = first; i < last; ++i) {
      search.candidates = static_cast<int>(i + 1);
      if (!(*screened)[i - first]) continue;
      ++search.confirmations;
      auto confirmed = grade_candidates(pool, {candidate_job(failed, all[i], budget, false)}, mesh_bytes);
      if (!confirmed) {
        report.warnings.push_back("the repair search could not run (" + confirmed.error().message + ")");
        return;
      }
      if (confirmed->front()) {
        report.repair_search = std::move(search);
        state_repair(*program, all[i], shown, report);
        return;
      }
      if (search.confirmations == budget.confirmations) {
        search.budget_spent = true;
        report.repair_search = std::move(search);
        return;
      }
    }
  }
  search.budget_spent = true;
  report.repair_search = std::move(search);
}

}  // namespace shadelab::road
