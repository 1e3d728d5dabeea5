#include "repair/classmate_edits.h"

#include <algorithm>
#include <set>
#include <string>
#include <tuple>

#include "repair/stage_tokens.h"
#include "shader/glsl_lines.h"

namespace shadelab::repair {

namespace {

// A stage's lines, unspaced, less the empty ones: what "written alike" compares.
std::set<std::string> line_set(const std::vector<std::string_view>& lines) {
  std::set<std::string> out;
  for (const auto line : lines)
    if (auto u = unspaced(line); !u.empty()) out.insert(std::move(u));
  return out;
}

size_t lines_alike(const std::set<std::string>& student, std::string_view classmate_glsl) {
  size_t n = 0;
  for (const auto& line : line_set(shader::lines_of(classmate_glsl))) n += student.contains(line);
  return n;
}

// The locals a stage declares (`vec3 reflectDir = ...`, `float spec;`): a type's name, then the
// name declared, then `=`, `;` or `,`.
std::set<std::string_view> declared_locals(const StageTokens& s) {
  std::set<std::string_view> out;
  for (size_t i = 1; i + 1 < s.size(); ++i)
    if (s.identifier(i - 1) && s.identifier(i) && (s.is(i + 1, "=") || s.is(i + 1, ";") || s.is(i + 1, ","))) out.insert(s.t[i].text);
  return out;
}

// Whether an edit's text names a local the classmate declares and the student's stage never
// writes at all: it cannot compile, and a screen of it would be spent for nothing.
bool names_a_local_missing(const RepairEdit& e, const std::set<std::string_view>& classmate_locals, const StageTokens& student) {
  for (const auto& token : shader::tokens_of(e.with)) {
    if (token.kind != shader::GlslToken::Kind::identifier || !classmate_locals.contains(token.text)) continue;
    if (std::none_of(student.t.begin(), student.t.end(), [&](const auto& t) { return t.text == token.text; })) return true;
  }
  return false;
}

// An edit by what it does to the student's text: two programs that offer the same are one offer.
using EditKey = std::tuple<shader::Stage, size_t, size_t, std::string>;
EditKey key_of(const RepairEdit& e) { return {e.stage, e.begin, e.end, e.with}; }

}  // namespace

std::vector<StagePair> nearest_classmates(const ProgramReading& student, const std::vector<StagePair>& classmates, size_t count) {
  const auto vertex = line_set(student.vertex.lines), fragment = line_set(student.fragment.lines);
  std::vector<std::pair<size_t, size_t>> alike;  // (lines alike, index), for the distinct programs
  std::set<std::pair<std::string_view, std::string_view>> seen;
  for (size_t i = 0; i < classmates.size(); ++i)
    if (seen.insert({classmates[i].vertex, classmates[i].fragment}).second)
      alike.push_back({lines_alike(vertex, classmates[i].vertex) + lines_alike(fragment, classmates[i].fragment), i});
  std::stable_sort(alike.begin(), alike.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<StagePair> out;
  for (size_t k = 0; k < alike.size() && k < count; ++k) out.push_back(classmates[alike[k].second]);
  return out;
}

std::vector<RepairEdit> classmate_edits(const StagePair& student, const StagePair& reference, const std::vector<StagePair>& classmates) {
  const ProgramReading read(student, reference);
  return classmate_edits(read, program_edits(read).live, classmates);
}

std::vector<RepairEdit> classmate_edits(const ProgramReading& student, const std::vector<RepairEdit>& reference_edits,
                                        const std::vector<StagePair>& classmates) {
  // program_edits keeps what could be the student's line (live, and not written as the program
  // beside it writes it); the course's reference's own offers are made already.
  std::set<EditKey> offered;
  for (const auto& e : reference_edits) offered.insert(key_of(e));
  std::vector<RepairEdit> out;
  for (const auto& glsl : classmates) {
    const ProgramReading beside(student.student(), glsl);
    const auto vertex_locals = declared_locals(beside.vertex.theirs), fragment_locals = declared_locals(beside.fragment.theirs);
    for (auto& e : program_edits(beside).live) {
      const bool reads = reads_reference(e.kind), inserts = inserts_statement(e.kind);
      if (!reads || !offered.insert(key_of(e)).second) continue;
      const StageReading& s = student[e.stage];
      if (names_a_local_missing(e, e.stage == shader::Stage::vertex ? vertex_locals : fragment_locals, s.student)) continue;
      // As with the reference's offers: a line the student wrote as the reference writes it is right.
      if (!inserts && s.written_as_theirs(e)) continue;
      e.reads_as_reference = inserts || s.reads_as_theirs_after(e);
      out.push_back(std::move(e));
    }
  }
  std::stable_sort(out.begin(), out.end(), smaller);
  return out;
}

}  // namespace shadelab::repair
