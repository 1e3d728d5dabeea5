#include "road/repair_search.h"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <future>
#include <thread>
#include <optional>
#include <regex>
#include <set>
#include <vector>

#include "grade/aligned_lines.h"
#include "grade/classmate_edits.h"
#include "grade/diagnosis.h"
#include "grade/repair_words.h"
#include "grade/starter_constants.h"
#include "shader/glsl_lines.h"
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
  std::vector<grade::RepairEdit> edits;  // one, or a pair
  shader::ShaderFile vertex, fragment;   // the program with the edits made
  bool from_class = false;               // a single a classmate's program offers (grade/classmate_edits.h)
};

struct Program {
  StudentStage vertex, fragment;
  std::string reference_vertex, reference_fragment;  // the GLSL the grade's reference draws with, or empty
  std::vector<std::pair<std::string, std::string>> classmates;  // each passing classmate's GLSL: vertex, fragment
  const StudentStage& operator[](shader::Stage s) const { return s == shader::Stage::vertex ? vertex : fragment; }
};

std::string glsl_or_empty(const shader::ShaderFile& file, shader::Stage stage) {
  auto unwrapped = shader::unwrap(file, stage);
  return unwrapped ? std::move(unwrapped->glsl) : std::string();
}

std::optional<Program> program_of(const worker::Job& job, const std::vector<PassingProgram>& classmates) {
  auto vertex = shader::unwrap(job.request.vertex, shader::Stage::vertex);
  auto fragment = shader::unwrap(job.request.fragment, shader::Stage::fragment);
  if (!vertex || !fragment) return std::nullopt;
  Program p{{&job.request.vertex, std::move(*vertex)},
            {&job.request.fragment, std::move(*fragment)},
            glsl_or_empty(job.grade.reference_vertex, shader::Stage::vertex),
            glsl_or_empty(job.grade.reference_fragment, shader::Stage::fragment),
            {}};
  for (const auto& c : classmates) {
    auto v = glsl_or_empty(c.vertex, shader::Stage::vertex), f = glsl_or_empty(c.fragment, shader::Stage::fragment);
    if (!v.empty() && !f.empty()) p.classmates.emplace_back(std::move(v), std::move(f));
  }
  return p;
}

// The program with `edits` made: an edited stage given as the GLSL the edits made (the same
// program the driver compiles), the other as the student's file.
Candidate candidate_of(const Program& p, std::vector<grade::RepairEdit> edits) {
  Candidate c{std::move(edits), *p.vertex.file, *p.fragment.file};
  for (const shader::Stage stage : {shader::Stage::vertex, shader::Stage::fragment}) {
    std::vector<grade::OtherStageSpan> here;  // each span this stage's text changes
    for (const auto& e : c.edits) {
      if (e.stage == stage) here.push_back({e.begin, e.end, e.with});
      else if (e.other_stage) here.push_back(*e.other_stage);
    }
    if (here.empty()) continue;
    // The later span first, so the earlier one's bytes are still where it says.
    std::sort(here.begin(), here.end(), [](const auto& a, const auto& b) { return a.begin > b.begin; });
    std::string glsl = p[stage].source.glsl;
    for (const auto& span : here) glsl = glsl.substr(0, span.begin) + span.with + glsl.substr(span.end);
    (stage == shader::Stage::vertex ? c.vertex : c.fragment).text = std::move(glsl);
  }
  return c;
}

// The edits the class's passing programs nearest the student's offer, beyond the reference's.
std::vector<grade::RepairEdit> class_edits(const Program& p, const grade::StagePair& student, const RepairBudget& budget) {
  if (p.classmates.empty() || budget.class_candidates <= 0 || p.reference_fragment.empty()) return {};
  std::vector<grade::StagePair> class_programs;
  for (const auto& [vertex, fragment] : p.classmates) class_programs.push_back({vertex, fragment});
  const auto nearest = grade::nearest_classmates(student, class_programs, static_cast<size_t>(std::max(0, budget.classmates)));
  return grade::classmate_edits(student, {p.reference_vertex, p.reference_fragment}, nearest);
}

// The budget's single edits: the first `budget.class_candidates` the class offers, where it is
// given, then, smallest first, the first `budget.candidates` of the student's own and the first
// `budget.reference_candidates` of those that read the reference. The class's come first because
// a class is given only to a second search, once the same program's first one confirmed none of
// the others: screened again they would fail again, and could spend the confirmations again.
std::vector<Candidate> single_candidates(const Program& p, const RepairBudget& budget) {
  int own = std::max(0, budget.candidates), reference = std::max(0, budget.reference_candidates);
  int from_class = std::max(0, budget.class_candidates);
  const grade::StagePair student{p.vertex.source.glsl, p.fragment.source.glsl};
  std::vector<Candidate> out;
  for (auto& e : class_edits(p, student, budget))
    if (from_class-- > 0) {
      out.push_back(candidate_of(p, {std::move(e)}));
      out.back().from_class = true;
    }
  for (auto& e : grade::program_repair_edits(student, {p.reference_vertex, p.reference_fragment}))
    if ((grade::reads_reference(e.kind) ? reference : own)-- > 0) out.push_back(candidate_of(p, {std::move(e)}));
  return out;
}

bool overlapping(const grade::RepairEdit& a, const grade::RepairEdit& b) {
  return a.stage == b.stage && a.begin <= b.end && b.begin <= a.end;  // touching spans count: one token's edits
}

// The grade's job for a candidate: a verdict only (no catalogue, no formula, no heat map), on the
// grade's canvas or, to screen (`screen`: the probes it keeps), one `budget.screen_size` on its
// longer side within its share of the deadlines.
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

worker::Job candidate_job(const worker::Job& failed, const Candidate& c, const RepairBudget& budget, const std::vector<std::string>* screen) {
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

// Which of the homework formula's `vectors` the edit's subject is, where it is a local of the
// student's fragment stage that stands for one of the reference fragment stage's (by the student's
// own name or the one aligned with it): the formula's name for it ("L") and its words; none else.
const VectorWords::value_type* vector_of(const Program& p, const grade::RepairEdit& e, const VectorWords& vectors) {
  if (vectors.empty() || e.stage != shader::Stage::fragment || p.reference_fragment.empty()) return nullptr;
  const std::string& glsl = p.fragment.source.glsl;
  const std::string name = grade::AlignedLines(glsl, p.reference_fragment).reference_name(e.subject, grade::edited_line(glsl, e));
  const auto found = vectors.find(name);
  return found == vectors.end() ? nullptr : &*found;
}

// One edit of a confirmed repair, said as far as `shown` allows.
grade::Repair repair_of(const Program& p, const grade::RepairEdit& e, grade::RepairShown shown, const VectorWords& vectors) {
  const StudentStage& stage = p[e.stage];
  const auto* vector = vector_of(p, e, vectors);
  grade::Repair repair{e.kind, std::nullopt, std::nullopt, grade::repair_words(e, vector ? std::string_view(vector->second) : ""),
                       std::nullopt, grade::repair_label(e, vector ? std::string_view(vector->first) : "")};
  if (shown != grade::RepairShown::what) {
    repair.file = stage.file->name.empty() ? std::string(to_string(e.stage)) : stage.file->name;
    repair.line = stage.source.locate(e.line, 0).file_line;
  }
  // A restored statement or value is the reference's text, not the student's line: named, never shown.
  if (shown == grade::RepairShown::repaired_line && !grade::writes_reference_text(e.kind))
    repair.repaired_line = grade::edited_line(stage.source.glsl, e);
  return repair;
}

// Where the grader named a changed starter constant ("your shader's exponent is 20.0; the
// course's starter uses 6.0", the first message: grade/judge_code.h) and `e` refits the number
// that line gives it, that message is the edit's words at its line: said once, not twice.
std::optional<std::string> constant_named(const Program& p, const grade::RepairEdit& e, const std::vector<grade::StarterConstant>& constants,
                                          const grade::Report& report) {
  if (e.kind != grade::RepairKind::literal_refit || e.stage != shader::Stage::fragment || report.messages.empty()) return std::nullopt;
  if (report.diagnosis.empty() || report.diagnosis == grade::to_string(grade::Diagnosis::nan)) return std::nullopt;
  const auto changed = grade::changed_starter_constants(constants, p.fragment.file->text);
  if (changed.size() != 1) return std::nullopt;  // which message names which constant is not ours to guess
  const std::regex gives("\\b" + changed.front().variable + "\\s*=");
  const std::string_view line = shader::line_of(p.fragment.source.glsl, e.line);
  if (!std::regex_search(line.begin(), line.end(), gives)) return std::nullopt;
  const std::string& message = report.messages.front();
  return message.ends_with('.') ? message : message + ".";
}

// The confirmed repair, said as far as `shown` allows: "phong_frag.js line 20: L is not normalised:
// ..." for each edit, then, with the repaired lines, "With `...` the frames match ...".
void state_repair(const Program& p, const Candidate& c, grade::RepairShown shown, const VectorWords& vectors,
                  const std::vector<grade::StarterConstant>& constants, grade::Report& report) {
  std::vector<grade::Repair> repairs;
  for (const auto& e : c.edits) repairs.push_back(repair_of(p, e, shown, vectors));
  std::vector<std::string> said, lines;
  bool constant_said = false;  // the grader's message on a changed constant, now at its line
  for (size_t i = 0; i < repairs.size(); ++i) {
    const grade::Repair& r = repairs[i];
    const auto named = constant_named(p, c.edits[i], constants, report);
    constant_said = constant_said || named;
    std::string text = named ? *named : r.text + ".";
    said.push_back((r.line ? *r.file + " line " + std::to_string(*r.line) + ": " : std::string()) + text);
  }
  // Every edit of the repair is in its sentence: a restored value (the reference's text, never
  // shown) by its line, so that a repair of two edits never reads as one.
  const bool shows_a_line = std::any_of(repairs.begin(), repairs.end(), [](const grade::Repair& r) { return r.repaired_line.has_value(); });
  for (const auto& r : repairs)
    if (shows_a_line) lines.push_back(r.repaired_line ? "`" + *r.repaired_line + "`" : r.file.value_or("") + " line " + std::to_string(r.line.value_or(0)) + " as the homework writes it");
  if (!lines.empty())
    said.push_back("With " + lines.front() + (lines.size() > 1 ? " and " + lines.back() : "") +
                   " the frames match the reference's on every frame and light the grade draws.");
  // The formula's "cannot say why" is superseded by what a render confirmed.
  auto& m = report.messages;
  if (report.explanation && !report.explanation->explained) m.erase(std::remove(m.begin(), m.end(), report.explanation->text), m.end());
  if (constant_said) m.erase(m.begin());
  m.insert(m.begin() + std::min<size_t>(constant_said ? 0 : 1, m.size()), said.begin(), said.end());
  report.repair_search->found = std::move(repairs.front());
  if (repairs.size() > 1) report.repair_search->also = std::move(repairs.back());
}

// What one pass of the search came to.
enum class Pass { confirmed, budget_spent, none_passed, trouble };

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
  Pass try_in_order(const std::vector<Candidate>& candidates, int confirmations, std::vector<double>* distances, const Candidate** winner) {
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

  Pass could_not_run(const Error& e) {
    report.warnings.push_back("the repair search could not run (" + e.message + ")");
    return Pass::trouble;
  }

  // The student's own program's distance on the screening canvas: what a single edit must improve
  // on to be one of a pair.
  std::optional<double> own_distance(const Program& p) {
    auto own = grade_candidates(pool, {candidate_job(failed, candidate_of(p, {}), budget, &probes)}, mesh);
    if (!own) {
      could_not_run(own.error());
      return std::nullopt;
    }
    return own->front().distance;
  }
};

// Pairs for a program no single edit repairs, at most `budget.pairs`, in this order:
// - two singles the class offers (two of a passing program's values, where the student's program
//   is written as that program is), in the singles' order;
// - two singles that each make their line read as the reference's (the student's program aligned
//   with the reference at two lines), in the singles' order;
// - the single that drew nearest the reference (a mistake of two mended: it must draw nearer than
//   the student's own program) with each other single, in the singles' order. A second mistake's
//   edit need not draw nearer alone: the first mistake's error can hide it.
// No pair twice, and none of two edits that touch.
std::vector<Candidate> pair_candidates(const Program& p, const std::vector<Candidate>& singles, const std::vector<double>& distances,
                                       double own, const RepairBudget& budget) {
  std::vector<Candidate> out;
  std::set<std::pair<size_t, size_t>> paired;
  const auto add = [&](size_t i, size_t j) {
    const grade::RepairEdit &a = singles[i].edits.front(), &b = singles[j].edits.front();
    if (i == j || overlapping(a, b) || out.size() >= static_cast<size_t>(std::max(0, budget.pairs))) return;
    if (!paired.insert(std::minmax(i, j)).second) return;
    out.push_back(candidate_of(p, smaller(b, a) ? std::vector{b, a} : std::vector{a, b}));
  };
  for (size_t i = 0; i < singles.size() && singles[i].from_class; ++i)
    for (size_t j = i + 1; j < singles.size() && singles[j].from_class; ++j) add(i, j);
  for (size_t i = 0; i < singles.size(); ++i)
    for (size_t j = i + 1; j < singles.size(); ++j)
      if (singles[i].edits.front().reads_as_reference && singles[j].edits.front().reads_as_reference) add(i, j);
  size_t nearest = distances.size();
  for (size_t i = 0; i < distances.size(); ++i)
    if (distances[i] < own && (nearest == distances.size() || distances[i] < distances[nearest])) nearest = i;
  if (nearest < distances.size())
    for (size_t i = 0; i < singles.size(); ++i) add(nearest, i);
  return out;
}

}  // namespace

bool class_offers_edits(const worker::Job& failed, const std::vector<PassingProgram>& classmates, const RepairBudget& budget) {
  const auto program = program_of(failed, classmates);
  return program && !class_edits(*program, {program->vertex.source.glsl, program->fragment.source.glsl}, budget).empty();
}

bool wants_repair(const grade::Report& report, const std::vector<grade::StarterConstant>& constants) {
  if (report.pass || report.frames.empty() || !report.diagnostics.empty()) return false;
  if (report.explanation && report.explanation->explained) return false;
  const auto changed = [&](const grade::StarterConstant& c) { return report.diagnosis == grade::changed_constant_diagnosis(c.variable); };
  return report.diagnosis.empty() || report.diagnosis == grade::to_string(grade::Diagnosis::nan) ||
         std::any_of(constants.begin(), constants.end(), changed);
}

void search_repair(worker::WorkerPool& pool, const worker::Job& failed, const std::string& mesh_bytes, grade::RepairShown shown,
                   const VectorWords& vectors, grade::Report& report, const RepairBudget& budget,
                   const std::vector<PassingProgram>& classmates) {
  const auto program = program_of(failed, classmates);
  if (!program || budget.confirmations < 1) return;  // nothing screened could be stated
  Search search{pool, failed, mesh_bytes, budget, report};
  const std::vector<Candidate> singles = single_candidates(*program, budget);
  std::vector<double> distances;
  std::vector<Candidate> pairs;
  const Candidate* winner = nullptr;  // in `singles` or `pairs`
  Pass pass = search.try_in_order(singles, budget.confirmations, &distances, &winner);
  // A single whose screen passed and whose full render did not is a mistake half mended: the
  // pairs still get confirmations of their own.
  if (pass != Pass::confirmed && pass != Pass::trouble && budget.pairs > 0 && budget.pair_confirmations > 0) {
    // No one edit repairs it: two edits (pair_candidates says which, in what order).
    const auto own = search.own_distance(*program);
    if (!own) return;
    pairs = pair_candidates(*program, singles, distances, *own, budget);
    pass = search.try_in_order(pairs, budget.pair_confirmations, nullptr, &winner);
  }
  if (pass == Pass::trouble) return;
  search.spent.budget_spent = pass != Pass::confirmed;
  report.repair_search = std::move(search.spent);
  if (winner) state_repair(*program, *winner, shown, vectors, failed.grade.starter_constants, report);
}

}  // namespace shadelab::road
