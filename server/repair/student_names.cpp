#include "repair/student_names.h"

#include <set>

#include "repair/aligned_lines.h"
#include "repair/stage_names.h"

namespace shadelab::repair {

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
