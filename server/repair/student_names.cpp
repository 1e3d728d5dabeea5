#include "repair/student_names.h"

#include <algorithm>
#include <functional>
#include <set>
#include <vector>

#include "repair/aligned_lines.h"
#include "repair/stage_names.h"

namespace shadelab::repair {

namespace {

// The locals of `type` a program declares that are not aligned: not in `aligned`, and not
// declared by the other program too (a name both declare is one variable).
std::vector<std::string> unaligned(const TypedNames& declared, const TypedNames& inputs, const TypedNames& other,
                                   const std::function<bool(const std::string&)>& aligned, const std::string& type) {
  std::vector<std::string> out;
  for (const auto& [name, t] : declared)
    if (t == type && !inputs.contains(name) && !other.contains(name) && !aligned(name)) out.push_back(name);
  return out;
}

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

// The one local of a type each program leaves unaligned, where each leaves exactly one: the
// student's `vec3 reflectDir = normalize(lightDir + viewDir);` is the reference's R, written
// otherwise (its declaration reads as none of the reference's, and no use of it aligns).
void pair_lone_locals(const StageTokens& s, const StageTokens& r, NameMap& out) {
  const TypedNames own = declared_types(s), theirs = declared_types(r), own_inputs = read_only_names(s), their_inputs = read_only_names(r);
  std::set<std::string> types;
  for (const auto& [name, type] : theirs) types.insert(type);
  for (const auto& type : types) {
    const auto student = unaligned(own, own_inputs, theirs, [&](const std::string& n) {
      return std::any_of(out.begin(), out.end(), [&](const auto& kv) { return kv.second == n; });
    }, type);
    const auto reference = unaligned(theirs, their_inputs, own, [&](const std::string& n) { return out.contains(n); }, type);
    if (student.size() == 1 && reference.size() == 1 && read_alike(s, student.front(), r, reference.front()))
      out.emplace(reference.front(), student.front());
  }
}

}  // namespace

NameMap student_names(const StageTokens& s, const StageTokens& r) {
  const AlignedLines lines(s, r);
  const TypedNames inputs = read_only_names(s);
  NameMap out;
  std::set<std::string> twice;
  for (const auto& [name, type] : declared_types(s)) {
    if (inputs.contains(name)) continue;
    const std::string theirs = lines.reference_name(name, "");
    if (theirs.empty() || theirs == name) continue;
    if (!out.emplace(theirs, name).second) twice.insert(theirs);
  }
  for (const auto& name : twice) out.erase(name);
  pair_lone_locals(s, r, out);
  return out;
}

std::optional<std::string> in_student_names(const StageTokens& s, const StageTokens& r, size_t first, size_t last, const NameMap& names,
                                            bool expand) {
  const TypedNames own = declared_types(s), inputs = read_only_names(s), theirs = declared_types(r);
  std::string out;
  for (size_t k = first; k <= last; ++k) {
    if (k > first) out += r.glsl.substr(r.end(k - 1), r.begin(k) - r.end(k - 1));
    const std::string_view token = r.t[k].text;
    if (!r.identifier(k) || r.is(k + 1, "(") || r.is(k - 1, ".") || inputs.contains(token) || (own.contains(token) && theirs.contains(token))) {
      out += token;
      continue;
    }
    if (const auto named = names.find(token); named != names.end()) {
      out += named->second;
      continue;
    }
    if (!expand || !theirs.contains(token)) return std::nullopt;
    std::optional<std::string> value;
    for (size_t d = 1; d + 2 < r.size() && !value; ++d) {
      if (!r.is(d, token) || !r.identifier(d - 1) || !r.is(d + 1, "=") || r.is(d + 2, "=")) continue;
      const size_t end = r.expression_last(d + 2);
      value = in_student_names(s, r, d + 2, end, names, false);
      if (value && r.operand_last(d + 2) != end) value = "(" + *value + ")";
    }
    if (!value) return std::nullopt;
    out += *value;
  }
  return out;
}

}  // namespace shadelab::repair
