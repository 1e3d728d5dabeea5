#include "repair/repair_candidates.h"

#include <algorithm>
#include <optional>
#include <set>

#include "repair/classmate_edits.h"
#include "shader/glsl_lines.h"

namespace shadelab::repair {

namespace {

std::string glsl_or_empty(const shader::ShaderFile& file, shader::Stage stage) {
  auto unwrapped = shader::unwrap(file, stage);
  return unwrapped ? std::move(unwrapped->glsl) : std::string();
}

bool class_may_offer(const RepairProgram& p, const CandidateCounts& counts) {
  return !p.classmates.empty() && counts.from_class > 0 && !p.read.beside_nothing();
}

// A classmate's stage the search may read: unwrapped, and within the budget a student's stage has.
bool readable(const std::string& glsl) { return !glsl.empty() && shader::tokens_of(glsl).size() <= kRepairTokensAStage; }

// Touching spans count (one token's edits), but for two values added after the same write: two
// unread terms both added (`fragColor += ambient; fragColor += specular;` where a sum left out both).
bool overlapping(const RepairEdit& a, const RepairEdit& b) {
  if (a.stage != b.stage) return false;
  const bool both_added = a.kind == RepairKind::value_added && b.kind == RepairKind::value_added && a.begin == a.end && b.begin == b.end;
  if (both_added && a.begin == b.begin) return a.with == b.with;
  return a.begin <= b.end && b.begin <= a.end;
}

}  // namespace

Expected<RepairProgram> repair_program(const shader::ShaderFile& vertex, const shader::ShaderFile& fragment,
                                       const shader::ShaderFile& reference_vertex, const shader::ShaderFile& reference_fragment,
                                       const std::vector<PassingProgram>& classmates) {
  // Every stage unwrapped first, then the student's read beside the reference within the budget.
  auto v = shader::unwrap(vertex, shader::Stage::vertex);
  auto f = shader::unwrap(fragment, shader::Stage::fragment);
  auto rv = shader::unwrap(reference_vertex, shader::Stage::vertex);
  auto rf = shader::unwrap(reference_fragment, shader::Stage::fragment);
  if (!v || !f) return Error{ErrorCode::invalid_argument, "a stage of the program cannot be unwrapped"};
  const auto glsl = [](const auto& unwrapped) { return unwrapped ? std::string_view(unwrapped->glsl) : std::string_view(); };
  auto read = ProgramReading::within({v->glsl, f->glsl}, {glsl(rv), glsl(rf)}, kRepairTokensAStage);
  if (!read) return read.take_error();
  RepairProgram p{{&vertex, std::move(*v)}, {&fragment, std::move(*f)}, std::move(*read), {}, {}};
  for (const auto& c : classmates) {
    auto cv = glsl_or_empty(c.vertex, shader::Stage::vertex), cf = glsl_or_empty(c.fragment, shader::Stage::fragment);
    if (readable(cv) && readable(cf)) p.classmates.emplace_back(std::move(cv), std::move(cf));
  }
  p.edits = program_edits(p.read);
  return p;
}

bool aligns(const RepairEdit& e) { return e.reads_as_reference || puts_back(e.kind) || e.edits_aligned_line; }

namespace {

// `p`'s stage `stage` with those of `edits` made that change it (a `flat` removed from both stages
// is one edit): the later span first, so the earlier one's bytes are still where it says (two at
// one point: in the edits' order). Empty where none changes it.
std::optional<std::string> edited_glsl(const RepairProgram& p, const std::vector<RepairEdit>& edits, shader::Stage stage) {
  std::vector<OtherStageSpan> here;  // each span this stage's text changes
  for (const auto& e : edits) {
    if (e.stage == stage) here.push_back({e.begin, e.end, e.with});
    else if (e.other_stage) here.push_back(*e.other_stage);
  }
  if (here.empty()) return std::nullopt;
  if (here.size() > 1) std::stable_sort(here.begin(), here.end(), [](const auto& a, const auto& b) { return a.begin > b.begin; });
  std::string glsl = p[stage].source.glsl;
  for (const auto& span : here) glsl = glsl.substr(0, span.begin) + span.with + glsl.substr(span.end);
  return glsl;
}

// The student's line that line `line` of the fragment stage with `e` made was: an edit that adds
// lines (a statement put back on a line of its own) moves the lines after it; none for a line the
// edit put in.
std::optional<int> line_before(const RepairProgram& p, const RepairEdit& e, int line) {
  if (e.stage != shader::Stage::fragment || line < e.line) return line;
  const std::string_view glsl = p.fragment.source.glsl;
  const auto added = std::count(e.with.begin(), e.with.end(), '\n') - std::count(glsl.begin() + e.begin, glsl.begin() + e.end, '\n');
  if (added > 0 && line < e.line + added) return std::nullopt;
  return line - static_cast<int>(added);
}

}  // namespace

RepairCandidate candidate_of(const RepairProgram& p, std::vector<RepairEdit> edits) {
  if (edits.size() > 1) std::stable_sort(edits.begin(), edits.end(), smaller);  // a pair is said in this order
  RepairCandidate c{std::move(edits), *p.vertex.file, *p.fragment.file};
  for (const shader::Stage stage : {shader::Stage::vertex, shader::Stage::fragment})
    if (auto glsl = edited_glsl(p, c.edits, stage)) (stage == shader::Stage::vertex ? c.vertex : c.fragment).text = std::move(*glsl);
  return c;
}

std::vector<RepairEdit> class_edits(const RepairProgram& p, const CandidateCounts& counts) {
  if (!class_may_offer(p, counts)) return {};
  std::vector<StagePair> class_programs;
  for (const auto& [vertex, fragment] : p.classmates) class_programs.push_back({vertex, fragment});
  const auto nearest = nearest_classmates(p.read, class_programs, static_cast<size_t>(std::max(0, counts.classmates)));
  return classmate_edits(p.read, p.edits.live, nearest);
}

std::vector<RepairCandidate> single_candidates(const RepairProgram& p, const CandidateCounts& counts) {
  int own_left = std::max(0, counts.own), reference_left = std::max(0, counts.reference), class_left = std::max(0, counts.from_class);
  std::vector<RepairCandidate> out;
  for (auto& e : class_edits(p, counts))
    if (class_left-- > 0) {
      out.push_back(candidate_of(p, {std::move(e)}));
      out.back().from_class = true;
    }
  for (const auto& e : p.edits.live)
    if ((reads_reference(e.kind) ? reference_left : own_left)-- > 0) out.push_back(candidate_of(p, {e}));
  return out;
}

std::vector<RepairCandidate> pair_candidates(const RepairProgram& p, const std::vector<RepairCandidate>& singles,
                                             const std::vector<double>& distances, double own, const CandidateCounts& counts) {
  std::vector<RepairCandidate> out;
  std::set<std::pair<size_t, size_t>> paired;
  const auto add = [&](size_t i, size_t j) {
    const RepairEdit &a = singles[i].edits.front(), &b = singles[j].edits.front();
    if (i == j || overlapping(a, b) || out.size() >= static_cast<size_t>(std::max(0, counts.pairs))) return;
    if (!paired.insert(std::minmax(i, j)).second) return;
    out.push_back(candidate_of(p, {a, b}));
  };
  for (size_t i = 0; i < singles.size() && singles[i].from_class; ++i)
    for (size_t j = i + 1; j < singles.size() && singles[j].from_class; ++j) add(i, j);
  // A single that puts back a term, a statement or a power, with each edit of a line only that
  // could make live (V's line, where the deleted term was all that read V; the exponent's, where
  // the left-out `pow` was all that read it): a mistake the missing part hid.
  for (size_t i = 0; i < singles.size() && !p.read.beside_nothing(); ++i) {
    const RepairEdit& a = singles[i].edits.front();
    if (!makes_live(a.kind)) continue;
    for (const RepairEdit& b : p.edits.dead) {
      if (out.size() >= static_cast<size_t>(std::max(0, counts.pairs))) break;
      if (!overlapping(a, b)) out.push_back(candidate_of(p, {a, b}));
    }
  }
  const auto aligned = [&](size_t i) { return aligns(singles[i].edits.front()); };
  for (size_t i = 0; i < singles.size(); ++i)
    for (size_t j = i + 1; j < singles.size(); ++j)
      if (aligned(i) && aligned(j)) add(i, j);
  size_t nearest = distances.size();
  for (size_t i = 0; i < distances.size(); ++i)
    if (distances[i] < own && (nearest == distances.size() || distances[i] < distances[nearest])) nearest = i;
  if (nearest < distances.size())
    for (size_t i = 0; i < singles.size(); ++i) add(nearest, i);
  return out;
}

Departures departing_after(const RepairProgram& p, const RepairCandidate& c, const ValueAgreement& values) {
  if (c.edits.size() != 1 || p.read.beside_nothing() || !values.read) return {};
  const auto stage = [&](shader::Stage s) { return edited_glsl(p, c.edits, s).value_or(p[s].source.glsl); };
  const std::string vertex = stage(shader::Stage::vertex), fragment = stage(shader::Stage::fragment);
  const ProgramReading edited({vertex, fragment}, {p.read.vertex.theirs.glsl, p.read.fragment.theirs.glsl});
  Departures out;
  for (const auto& [line, changes] : departures(edited, values))
    if (const auto before = line_before(p, c.edits.front(), line); before && *before != c.edits.front().line) out[*before] = changes;
  return out;
}

std::vector<RepairCandidate> pairs_with(const RepairProgram& p, const RepairEdit& nearest, const std::vector<RepairCandidate>& singles,
                                        const std::set<int>& lines, const CandidateCounts& counts) {
  std::vector<RepairCandidate> out;
  for (const auto& single : singles) {
    if (out.size() >= static_cast<size_t>(std::max(0, counts.pairs))) break;
    const RepairEdit& e = single.edits.front();
    if (single.edits.size() != 1 || e.stage != shader::Stage::fragment || lines.count(e.line) == 0 || overlapping(nearest, e)) continue;
    out.push_back(candidate_of(p, {nearest, e}));
  }
  return out;
}

}  // namespace shadelab::repair
