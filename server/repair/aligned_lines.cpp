#include "repair/aligned_lines.h"

#include <algorithm>
#include <array>
#include <functional>
#include <set>

#include "repair/stage_names.h"
#include "shader/glsl_lines.h"

namespace shadelab::repair {

namespace {

// A line's tokens as text (comments are not tokens).
std::vector<std::string> tokens(std::string_view line) {
  std::vector<std::string> out;
  for (const auto& t : shader::tokens_of(line)) out.emplace_back(t.text);
  return out;
}

bool type_keyword(std::string_view s) {
  static constexpr std::array<std::string_view, 19> kTypes = {"float", "int",   "uint",  "bool",  "vec2",  "vec3",  "vec4",
                                                             "ivec2", "ivec3", "ivec4", "uvec2", "uvec3", "uvec4", "bvec2",
                                                             "bvec3", "bvec4", "mat2",  "mat3",  "mat4"};
  return std::find(kTypes.begin(), kTypes.end(), s) != kTypes.end();
}

// The token a local declaration declares (`vec3 L = ...;`, `const float a = ...;`, `vec3 L;`), or
// size() where the line declares none.
size_t declared_at(const std::vector<std::string>& t) {
  const size_t type = !t.empty() && t.front() == "const" ? 1 : 0;
  if (t.size() < type + 3 || !type_keyword(t[type])) return t.size();
  return t[type + 2] == "=" || t[type + 2] == ";" ? type + 1 : t.size();
}

// Each line's tokens, as text: a token is on the line it starts on (a comment is none, over as
// many lines as it runs).
std::vector<std::vector<std::string>> line_tokens(const StageTokens& s) {
  std::vector<std::vector<std::string>> lines(static_cast<size_t>(std::count(s.glsl.begin(), s.glsl.end(), '\n')) + 1);
  for (const auto& t : s.t) lines[static_cast<size_t>(t.line) - 1].emplace_back(t.text);
  return lines;
}

bool is_identifier(const std::string& s) { return !s.empty() && shader::identifier_start(s.front()); }

// The calls a local is read as an argument of (`dot` for `dot(V, R)`; "" for none).
std::set<std::string, std::less<>> calls_reading(const StageTokens& s, const std::string& name) {
  std::set<std::string, std::less<>> out;
  for (size_t i = 0; i < s.size(); ++i)
    if (s.is(i, name) && read_at(s, i)) out.emplace(s.enclosing_call(i));
  return out;
}

// Whether two locals are read alike: as an argument of one call in both programs, or outside any
// in both (`spec * uSpecularColor` is no `pow(..., specularAlpha)`).
bool read_alike(const StageTokens& s, const std::string& own, const StageTokens& r, const std::string& theirs) {
  const auto mine = calls_reading(s, own), their = calls_reading(r, theirs);
  return std::any_of(mine.begin(), mine.end(), [&](const std::string& call) { return their.contains(call); });
}

}  // namespace

AlignedLines::AlignedLines(std::string_view student_glsl, std::string_view reference_glsl)
    : AlignedLines(StageTokens(student_glsl, shader::Stage::fragment), StageTokens(reference_glsl, shader::Stage::fragment)) {}

AlignedLines::AlignedLines(const StageTokens& student, const StageTokens& reference)
    : reference_lines_(line_tokens(reference)), student_lines_(line_tokens(student)) {
  for (const Tokens& line : reference_lines_)
    if (const size_t at = declared_at(line); at < line.size()) names_.reference_declares.insert(line[at]);
  for (const Tokens& line : student_lines_)
    if (const size_t at = declared_at(line); at < line.size()) names_.student_declares.insert(line[at]);
  // In the order the student wrote them, and again while a pass aligns more: a helper written
  // above main declares `vec3 r = reflect(-l, n);` before main's lines align l and n. Where no
  // declaration aligns any more, a local the student uses where the reference uses one of its own
  // (`stands_for`) is aligned, and the declarations read again: `vec3 l = uLightPosition -
  // vPosition;` (not normalised) is L by its uses, so `vec3 r = reflect(-l, n);` is R.
  const auto align = [&](std::pair<std::string, std::string> names) {
    if (!names_.to_reference.insert(names).second) return false;
    names_.from_reference.emplace(names.second, names.first);
    return true;
  };
  // Surer ways first: a guess (a use beside a local neither has aligned) only where none of them
  // aligns any more, one at a time, and the surer ways again after it.
  const auto by_use = [&](Neighbours neighbours) {
    for (const auto& name : names_.student_declares) {
      if (names_.to_reference.contains(name) || names_.reference_declares.contains(name)) continue;
      bool guess = false;
      if (std::string theirs = stands_for(name, &guess, neighbours); !theirs.empty() && align({name, std::move(theirs)})) {
        if (guess) guessed_.insert(name);
        return true;  // one at a time: the next reads its uses with this one aligned
      }
    }
    return false;
  };
  for (bool more = true; more;) {
    more = false;
    for (const Tokens& line : student_lines_) {
      std::pair<std::string, std::string> declared;
      if (reads_as_reference(line, declared) && !declared.first.empty()) more = align(declared) || more;
    }
    more = more || by_use(Neighbours::aligned) || align_lone_local(student, reference, align) || by_use(Neighbours::unaligned_too);
  }
}

// Where no declaration and no use aligns any more: the one local of a type each program leaves
// unaligned, where each leaves exactly one and both are read as an argument of one call. The
// student's `vec3 reflectDir = normalize(lightDir + viewDir);` is the reference's R written
// otherwise: its declaration reads as none of the reference's, and no use of it aligns.
bool AlignedLines::align_lone_local(const StageTokens& student, const StageTokens& reference,
                                    const std::function<bool(std::pair<std::string, std::string>)>& align) {
  const TypedNames own = declared_types(student), theirs = declared_types(reference);
  const auto lone = [](const std::set<std::string, std::less<>>& declared, const TypedNames& types, const auto& unaligned, const std::string& type) {
    std::vector<std::string> out;
    for (const auto& name : declared)
      if (const auto t = types.find(name); t != types.end() && t->second == type && unaligned(name)) out.push_back(name);
    return out;
  };
  std::set<std::string> types;
  for (const auto& name : names_.reference_declares)
    if (const auto t = theirs.find(name); t != theirs.end()) types.insert(t->second);
  for (const auto& type : types) {
    const auto s = lone(names_.student_declares, own, [&](const std::string& n) { return student_unaligned(n); }, type);
    const auto r = lone(names_.reference_declares, theirs, [&](const std::string& n) { return reference_unaligned(n); }, type);
    if (s.size() == 1 && r.size() == 1 && read_alike(student, s.front(), reference, r.front()) && align({s.front(), r.front()})) {
      if (!guessed_.empty()) guessed_.insert(s.front());  // the one left beside a guess is one too
      return true;
    }
  }
  return false;
}

bool AlignedLines::reads_as_reference(std::string_view line) const {
  std::pair<std::string, std::string> declared;
  return reads_as_reference(tokens(line), declared);
}

std::string AlignedLines::reference_name(std::string_view name, std::string_view line, bool* guessed) const {
  if (guessed) *guessed = guessed_.contains(name);
  if (const auto to = names_.to_reference.find(name); to != names_.to_reference.end()) return to->second;
  if (names_.student_declares.contains(name) && names_.reference_declares.contains(name)) return std::string(name);
  std::pair<std::string, std::string> declared;
  if (reads_as_reference(tokens(line), declared) && declared.first == name) return declared.second;
  // Only a local the student declares stands in for one: a uniform or an input is what it is.
  return names_.student_declares.contains(name) ? stands_for(name, guessed, Neighbours::aligned) : std::string();
}

std::string AlignedLines::stands_for(std::string_view name, bool* guessed, Neighbours neighbours) const {
  std::string found;
  bool guess = false;
  for (const Tokens& s : student_lines_)
    for (size_t i = 0; i < s.size(); ++i) {
      if (s[i] != name) continue;
      for (const Tokens& r : reference_lines_)
        for (size_t j = 0; j < r.size(); ++j) {
          const std::string& local = r[j];
          if (!names_.reference_declares.contains(local) || names_.from_reference.contains(local) || names_.student_declares.contains(local))
            continue;
          bool beside_unaligned = false;
          if (!alike_around(s, i, r, j, neighbours, beside_unaligned)) continue;
          if (!found.empty() && found != local) return {};  // two places disagree: the grader cannot tell which
          found = local;
          guess = guess || beside_unaligned;
        }
    }
  if (guessed && !found.empty()) *guessed = *guessed || guess;
  return found;
}

bool AlignedLines::alike_around(const Tokens& student, size_t at, const Tokens& reference, size_t reference_at, Neighbours neighbours,
                                bool& beside_unaligned) const {
  constexpr size_t kAround = 2;
  if (at < kAround || reference_at < kAround || at + kAround >= student.size() || reference_at + kAround >= reference.size()) return false;
  const auto alike = [&](const std::string& s, const std::string& r) {
    if (same_token(s, r)) return true;
    const bool both = neighbours == Neighbours::unaligned_too && student_unaligned(s) && reference_unaligned(r);
    beside_unaligned = beside_unaligned || both;
    return both;
  };
  for (size_t k = 1; k <= kAround; ++k)
    if (!alike(student[at - k], reference[reference_at - k]) || !alike(student[at + k], reference[reference_at + k])) return false;
  return true;
}

bool AlignedLines::student_unaligned(const std::string& s) const {
  return names_.student_declares.contains(s) && !names_.reference_declares.contains(s) && !names_.to_reference.contains(s);
}

bool AlignedLines::reference_unaligned(const std::string& r) const {
  return names_.reference_declares.contains(r) && !names_.student_declares.contains(r) && !names_.from_reference.contains(r);
}

bool AlignedLines::same_token(const std::string& s, const std::string& r) const {
  if (!is_identifier(s) || !is_identifier(r)) return s == r;
  if (const auto to = names_.to_reference.find(s); to != names_.to_reference.end()) return to->second == r;
  return s == r && !names_.from_reference.contains(r);
}

bool AlignedLines::reads_as_reference(const Tokens& line, std::pair<std::string, std::string>& declared) const {
  return std::any_of(reference_lines_.begin(), reference_lines_.end(), [&](const Tokens& r) { return aligned(line, r, names_, declared); });
}

bool AlignedLines::aligned(const Tokens& student, const Tokens& reference, const Names& names, std::pair<std::string, std::string>& declared) {
  if (student.size() != reference.size()) return false;
  const size_t at = declared_at(student);
  std::pair<std::string, std::string> found;
  for (size_t i = 0; i < student.size(); ++i) {
    const std::string &s = student[i], &r = reference[i];
    if (!is_identifier(s) || !is_identifier(r)) {
      if (s != r) return false;
      continue;
    }
    // A name aligned with another never reads as itself, nor one the reference's aligned name took.
    const auto to = names.to_reference.find(s);
    const auto from = names.from_reference.find(r);
    if (to != names.to_reference.end() || from != names.from_reference.end()) {
      if (to == names.to_reference.end() || to->second != r) return false;
      continue;
    }
    if (s == r) continue;
    // Only the declared name aligns anew, and only with a name the other program does not declare.
    if (i != at || at != declared_at(reference) || names.reference_declares.contains(s) || names.student_declares.contains(r)) return false;
    found = {s, r};
  }
  declared = std::move(found);
  return true;
}

}  // namespace shadelab::repair
