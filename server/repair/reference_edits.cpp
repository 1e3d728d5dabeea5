#include "repair/reference_edits.h"

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <set>

#include "core/words.h"
#include "repair/stage_names.h"
#include "repair/stage_tokens.h"
#include "repair/student_names.h"
#include "repair/value_difference.h"
#include "repair/value_variation.h"

namespace shadelab::repair {

namespace {

using Stage = StageTokens;

// The number tokens of a stage outside its directives (`#version 300 es`).
std::vector<size_t> numbers_of(const Stage& s) {
  std::set<int> directive_lines;
  for (size_t i = 0; i < s.size(); ++i)
    if (s.is(i, "#") && (i == 0 || s.t[i - 1].line != s.t[i].line)) directive_lines.insert(s.t[i].line);
  std::vector<size_t> out;
  for (size_t i = 0; i < s.size(); ++i)
    if (s.number(i) && !directive_lines.contains(s.t[i].line)) out.push_back(i);
  return out;
}

bool is_float(std::string_view number) {
  return !number.starts_with("0x") && !number.starts_with("0X") && number.find_first_of(".eE") != std::string_view::npos;
}

double value_of(std::string_view number) { return std::strtod(std::string(number).c_str(), nullptr); }

// A number the reference's stage never writes, refit to each it does, floats to floats and
// integers to integers: max(0.5, X) -> max(0.0, X). A number the reference writes is left as it is.
void literals(const Stage& s, const Stage& reference, std::vector<RepairEdit>& out) {
  std::vector<std::string_view> offered;  // the reference's numbers, one of each value and kind, in order
  const auto offers = [&](std::string_view n) {
    return std::any_of(offered.begin(), offered.end(), [&](auto o) { return is_float(o) == is_float(n) && value_of(o) == value_of(n); });
  };
  for (const size_t i : numbers_of(reference))
    if (!offers(reference.t[i].text)) offered.push_back(reference.t[i].text);
  for (const size_t i : numbers_of(s)) {
    const std::string_view n = s.t[i].text;
    if (offers(n)) continue;
    for (const auto o : offered) {
      if (is_float(o) != is_float(n)) continue;
      RepairEdit e = s.replace(RepairKind::literal_refit, i, i, std::string(o), n);
      e.other = e.with;
      out.push_back(std::move(e));
    }
  }
}

// Operands (names and numbers) among tokens first..last: a restored value's size.
int operands(const Stage& s, size_t first, size_t last) {
  int n = 0;
  for (size_t k = first; k <= last && k < s.size(); ++k) n += s.identifier(k) || s.number(k);
  return n;
}

// The names a stage's results leave by: its `out` variables (a vertex stage's `varying`s too),
// gl_Position in a vertex stage, gl_FragColor in a fragment stage.
std::vector<std::string_view> outputs_of(const Stage& s) {
  std::vector<std::string_view> out{s.stage == shader::Stage::vertex ? "gl_Position" : "gl_FragColor"};
  for (size_t i = 0; i + 2 < s.size(); ++i) {
    if (!s.is(i, "out") && !(s.stage == shader::Stage::vertex && s.is(i, "varying"))) continue;
    size_t k = i + 1;
    while (k < s.size() && one_of(s.t[k].text, {"lowp", "mediump", "highp", "flat", "smooth", "centroid"})) ++k;
    if (s.identifier(k) && s.identifier(k + 1) && s.is(k + 2, ";")) out.push_back(s.t[k + 1].text);
  }
  return out;
}

// Where the stage assigns `name` (name = X, name += X, name.xyz = X, name[i] = X) as a statement:
// the token of the name, or size() when it never does.
size_t assignment_of(const Stage& s, std::string_view name) {
  for (size_t i = 1; i < s.size(); ++i) {
    if (!s.is(i, name) || !one_of(s.t[i - 1].text, {";", "{", "}", ")"})) continue;
    size_t k = i + 1;
    while (k + 1 < s.size() && (s.is(k, ".") || s.is(k, "["))) k = s.is(k, ".") ? k + 2 : s.close_of(k) + 1;
    if (k + 1 < s.size() && one_of(s.t[k].text, {"+", "-", "*", "/"})) ++k;
    if (s.is(k, "=") && !s.is(k + 1, "=")) return i;
  }
  return s.size();
}

// The `}` that closes the block opening at `open`, or size().
size_t block_end(const Stage& s, size_t open) {
  for (int depth = 0; open < s.size(); ++open) {
    if (s.is(open, "{")) ++depth;
    if (s.is(open, "}") && --depth == 0) return open;
  }
  return s.size();
}

bool statement_boundary(const Stage& s, size_t i) { return s.is(i, ";") || s.is(i, "{") || s.is(i, "}"); }

// The statement boundary (`;`, `{` or `}`) before token `at`.
size_t boundary_before(const Stage& s, size_t at) {
  while (at-- > 0)
    if (statement_boundary(s, at)) return at;
  return s.size();
}

// The name the statement after boundary `b` writes: `L` in `vec3 L = X;`, `color` in `color += X;`.
std::string_view target_after(const Stage& s, size_t b) {
  size_t k = b + 1;
  if (s.identifier(k) && s.identifier(k + 1)) ++k;  // a declaration's type
  return s.identifier(k) ? s.t[k].text : std::string_view();
}

// The `;` of the student's statement that writes or declares `name`, or size().
size_t statement_end_of(const Stage& s, std::string_view name) {
  for (size_t i = 1; i < s.size(); ++i) {
    if (!s.is(i, name)) continue;
    const bool starts = statement_boundary(s, i - 1) || (s.identifier(i - 1) && i >= 2 && statement_boundary(s, i - 2));
    const size_t end = s.expression_last(i) + 1;
    if (starts && s.is(end, ";")) return end;
  }
  return s.size();
}

// Where the reference's statement at `at` goes in the student's stage: after the token this
// returns. Aligned by the statements before it: after the student's statement that writes what
// the nearest of them writes; with none, at the start of main (it was the first) or its end.
size_t aligned_after(const Stage& s, const Stage& reference, size_t at) {
  for (size_t b = boundary_before(reference, at); b < reference.size(); b = boundary_before(reference, b)) {
    if (reference.is(b, "{")) return main_start(reference) == b ? main_start(s) : s.size();
    if (reference.is(b, "}")) break;  // a block before it: no statement to align with
    const size_t found = statement_end_of(s, target_after(reference, boundary_before(reference, b)));
    if (found < s.size()) return found;
  }
  const size_t end = block_end(s, main_start(s));
  return end < s.size() ? end - 1 : s.size();
}

// The reference's statement `at`..`last` (its `;`), inserted where it stands in the reference,
// by the statements before it, on the gap's last line before the next statement (where a
// deleted line was); none where no place aligns.
std::optional<RepairEdit> inserted(const Stage& s, const Stage& reference, size_t at, size_t last, RepairKind kind, std::string_view name) {
  const size_t after = aligned_after(s, reference, at);
  if (after + 1 >= s.size()) return std::nullopt;
  const size_t next = after + 1;
  const std::string statement(reference.text(at, last));
  RepairEdit e;
  if (s.t[next].line == s.t[after].line) {
    e = s.edit(kind, s.end(after), s.end(after), " " + statement, after, name);
  } else {
    // As many lines after the statement before it as in the reference, within the gap before
    // the next statement; at the next statement's own line where there is no gap.
    const int below = std::max(1, reference.t[at].line - reference.t[boundary_before(reference, at)].line);
    const int line = std::min(s.t[after].line + below, s.t[next].line);
    size_t line_start = s.glsl.rfind('\n', s.begin(next) - 1) + 1;
    for (int l = s.t[next].line; l > line; --l) line_start = s.glsl.rfind('\n', line_start - 2) + 1;
    e = s.edit(kind, line_start, line_start, "    " + statement + "\n", next, name);
    e.line = line;
  }
  e.nodes = operands(reference, at, last);
  return e;
}

// An output the student's stage never writes, where the reference's stage writes it: the
// reference's statement put back where it stands in the reference.
void restored_statements(const Stage& s, const Stage& reference, std::vector<RepairEdit>& out) {
  for (const std::string_view name : outputs_of(s)) {
    if (assignment_of(s, name) < s.size()) continue;
    const size_t at = assignment_of(reference, name);
    if (at >= reference.size()) continue;
    const size_t last = reference.expression_last(at) + 1;  // the statement's `;`
    if (!reference.is(last, ";")) continue;
    if (auto e = inserted(s, reference, at, last, RepairKind::statement_restored, name)) out.push_back(std::move(*e));
  }
}

// The statements that write `name` (declared, assigned or updated): each the token of the name.
std::vector<size_t> writes_of(const Stage& s, std::string_view name) {
  std::vector<size_t> out;
  for (size_t i = 1; i + 1 < s.size(); ++i) {
    if (!s.is(i, name)) continue;
    const bool declared = s.identifier(i - 1) && i >= 2 && statement_boundary(s, i - 2);
    if (declared && s.is(i + 1, "=")) out.push_back(i);
    else if (!declared && statement_boundary(s, i - 1) && assignment_of(s, name) <= i) out.push_back(i);
  }
  return out;
}

// Where the value a write at `i` assigns starts (`name = X`, `name += X`), or `i` where it is not
// one of those two forms (a field, an index).
size_t value_first(const Stage& s, size_t i) {
  if (s.is(i + 1, "=") && !s.is(i + 2, "=")) return i + 2;
  if (i + 2 < s.size() && one_of(s.t[i + 1].text, {"+", "-", "*", "/"}) && s.is(i + 2, "=")) return i + 3;
  return i;
}

// The statements that write the whole of `name` with `=` or an operator's `=` (a field's or an
// element's write, `color.r += 1.0;`, is left out: a student's extra touch, not a statement
// the two stages align by).
std::vector<size_t> whole_writes_of(const Stage& s, std::string_view name) {
  auto out = writes_of(s, name);
  std::erase_if(out, [&](size_t i) { return value_first(s, i) == i; });
  return out;
}

// How a write at `i` writes its name: "=", or the operator of `+=`, `-=`, `*=`, `/=`.
std::string_view operator_of(const Stage& s, size_t i) { return s.t[i + 1].text; }

// A write of a name the student's stage leaves out, where it writes the name otherwise as the
// reference does (the same operators, in order, but one): `color += ...;` deleted from the guard
// gets the reference's statement back, where it stands in the reference. A declaration is never
// one: without it the stage does not compile.
void restored_writes(const Stage& s, const Stage& reference, std::vector<RepairEdit>& out) {
  std::set<std::string_view, std::less<>> seen;
  for (size_t i = 1; i + 2 < reference.size(); ++i) {
    if (!reference.identifier(i) || !seen.insert(reference.t[i].text).second) continue;
    const std::string_view name = reference.t[i].text;
    const auto own = whole_writes_of(s, name), theirs = whole_writes_of(reference, name);
    if (own.empty() || theirs.size() != own.size() + 1) continue;
    for (size_t left_out = 0; left_out < theirs.size(); ++left_out) {
      const size_t at = theirs[left_out];
      if (!statement_boundary(reference, at - 1)) continue;  // a declaration
      bool aligned = true;
      for (size_t w = 0, k = 0; w < theirs.size() && aligned; ++w)
        if (w != left_out) aligned = operator_of(reference, theirs[w]) == operator_of(s, own[k++]);
      const size_t last = reference.expression_last(value_first(reference, at)) + 1;
      if (!aligned || !reference.is(last, ";")) continue;
      if (auto e = inserted(s, reference, at, last, RepairKind::write_restored, name)) out.push_back(std::move(*e));
    }
  }
}

// A value the student's stage computes otherwise than the reference's, where each writes the
// name as often, in the same order and with the same operators (`vec4 color = ...;` then `color
// += ...;`): the reference's value in its place (`vec3 R = normalize(L + V);` gets the reference's
// value of R; the first write of `color` that left the diffuse term out gets it back).
void restored_values(const Stage& s, const Stage& reference, std::vector<RepairEdit>& out) {
  std::set<std::string_view, std::less<>> seen;
  const StageVariation student_varies(s.t), reference_varies(reference.t);
  const NameMap names = student_names(s, reference);
  NameMap reference_names;  // the student's name -> the reference's, where the two differ
  for (const auto& [theirs, own] : names) reference_names.emplace(own, theirs);
  for (size_t i = 1; i + 2 < s.size(); ++i) {
    if (!s.identifier(i) || !s.is(i + 1, "=") || s.is(i + 2, "=") || !seen.insert(s.t[i].text).second) continue;
    const std::string_view name = s.t[i].text;
    const auto aligned = reference_names.find(name);
    const std::string_view reference_name = aligned == reference_names.end() ? name : std::string_view(aligned->second);
    const auto own = whole_writes_of(s, name), theirs = whole_writes_of(reference, reference_name);
    if (own.size() != theirs.size()) continue;
    for (size_t w = 0; w < own.size(); ++w) {
      const size_t first = value_first(s, own[w]), ref_first = value_first(reference, theirs[w]);
      if (first == own[w] || ref_first == theirs[w] || s.t[first - 1].text != reference.t[ref_first - 1].text ||
          s.t[own[w] + 1].text != reference.t[theirs[w] + 1].text)
        continue;  // not the same form of write
      const size_t last = s.expression_last(first), ref_last = reference.expression_last(ref_first);
      if (last < first || ref_last < ref_first) continue;
      // The reference's value, in the student's names where the student names the local otherwise
      // (`vec3 toEye = normalize(-vPosition)` for `vec3 V = ...`). A local both name alike gets the
      // reference's text as it is: a value of it in other names would draw as the reference at a
      // line that sums what the student's mistake, elsewhere, computed.
      const auto restored = aligned == reference_names.end() ? std::optional<std::string>(reference.text(ref_first, ref_last))
                                                             : in_student_names(s, reference, ref_first, ref_last, names);
      if (!restored || unspaced(s.text(first, last)) == unspaced(*restored)) continue;
      RepairEdit e = s.replace(RepairKind::value_restored, first, last, *restored, name);
      e.nodes = operands(reference, ref_first, ref_last);
      const std::vector<GlslToken> restored_tokens = shader::tokens_of(*restored);
      const std::span<const GlslToken> student_value(s.t.begin() + first, last - first + 1), reference_value(restored_tokens),
          as_the_reference_writes_it(reference.t.begin() + ref_first, ref_last - ref_first + 1);
      if (const auto d = value_difference(student_value, reference_value, name)) {
        e.said_as = d->said_as;
        e.subject = d->subject;
        e.other = d->other;
        e.homework_matrix = d->homework_matrix;
      } else if (student_varies.constant(student_value) && reference_varies.varies(as_the_reference_writes_it)) {
        e.constant_value = true;
        std::vector<std::string> inputs;
        for (const auto& input : reference_varies.inputs_read(as_the_reference_writes_it)) inputs.push_back("`" + input + "`");
        e.other = and_list(inputs);
      }
      out.push_back(std::move(e));
    }
  }
}

// A condition the student's stage tests otherwise than the reference's: each of the student's
// conditions the reference never tests, replaced by each the reference tests that the student's
// never does (`if (true)` gets `if (NdotL > 0.0)`). Not aligned by count: a student's extra `if`
// must not hide the one they changed. Few: most stages have one or two.
void restored_conditions(const Stage& s, const Stage& reference, std::vector<RepairEdit>& out) {
  const auto own = conditions_of(s), theirs = conditions_of(reference);
  const auto tested = [](const Stage& in, const auto& conditions, std::string_view text) {
    return std::any_of(conditions.begin(), conditions.end(), [&](const auto& c) { return unspaced(in.text(c.first, c.second)) == unspaced(text); });
  };
  for (const auto& [first, last] : own) {
    if (tested(reference, theirs, s.text(first, last))) continue;
    for (const auto& [ref_first, ref_last] : theirs) {
      if (tested(s, own, reference.text(ref_first, ref_last))) continue;
      RepairEdit e = s.replace(RepairKind::condition_restored, first, last, std::string(reference.text(ref_first, ref_last)), s.text(first, last));
      e.nodes = operands(reference, ref_first, ref_last);
      out.push_back(std::move(e));
    }
  }
}

}  // namespace

std::vector<RepairEdit> reference_edits(const Stage& s, const Stage& r) {
  std::vector<RepairEdit> out;
  literals(s, r, out);
  restored_statements(s, r, out);
  restored_writes(s, r, out);
  restored_values(s, r, out);
  restored_conditions(s, r, out);
  std::stable_sort(out.begin(), out.end(), smaller);
  return out;
}

}  // namespace shadelab::repair
