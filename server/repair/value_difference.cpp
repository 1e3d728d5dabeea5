#include "repair/value_difference.h"

#include <algorithm>
#include <cstdlib>

namespace shadelab::repair {

namespace {

using Tokens = std::span<const shader::GlslToken>;
using Kind = shader::GlslToken::Kind;

bool is(Tokens t, size_t i, std::string_view s) { return i < t.size() && t[i].text == s; }
bool operand_token(Tokens t, size_t i) { return i < t.size() && t[i].kind != Kind::punctuation; }

bool same(Tokens a, Tokens b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const auto& x, const auto& y) { return x.text == y.text; });
}

// Tokens as the student wrote them, their spaces included (every token is a view of one stage's GLSL).
std::string written(Tokens t) {
  if (t.empty()) return {};
  return std::string(t.front().text.data(), t.back().text.data() + t.back().text.size());
}

// The `)` or `]` that closes the bracket at `open`, or size().
size_t close_of(Tokens t, size_t open) {
  int depth = 0;
  for (size_t i = open; i < t.size(); ++i) {
    if (is(t, i, "(") || is(t, i, "[")) ++depth;
    if ((is(t, i, ")") || is(t, i, "]")) && --depth == 0) return i;
  }
  return t.size();
}

// The last token of the operand starting at `first` (a name or number, a call, a parenthesis,
// each with its fields and indices), or size() where none starts there.
size_t operand_last(Tokens t, size_t first) {
  size_t i = first;
  if (is(t, i, "(")) i = close_of(t, i);
  else if (operand_token(t, i) && is(t, i + 1, "(")) i = close_of(t, i + 1);
  else if (!operand_token(t, i)) return t.size();
  while (i + 2 < t.size() && (is(t, i + 1, ".") || is(t, i + 1, "["))) i = is(t, i + 1, ".") ? i + 2 : close_of(t, i + 1);
  return i;
}

// The last token of the term starting at `first`: its operands and the `*` and `/` between them.
size_t term_last(Tokens t, size_t first) {
  size_t i = operand_last(t, first);
  while (i + 2 < t.size() && (is(t, i + 1, "*") || is(t, i + 1, "/")) && operand_last(t, i + 2) < t.size()) i = operand_last(t, i + 2);
  return i;
}

bool one_operand(Tokens t) { return !t.empty() && operand_last(t, 0) == t.size() - 1; }

// `t` without the parentheses that wrap all of it: `(uLightPosition - vPosition)` reads as its inside.
Tokens unwrapped(Tokens t) {
  while (t.size() >= 2 && is(t, 0, "(") && close_of(t, 0) == t.size() - 1) t = t.subspan(1, t.size() - 2);
  return t;
}

// The arguments of `f(...)` where that call is all of `t`; none where it is not.
std::optional<std::vector<Tokens>> call_of(Tokens t, std::string_view f) {
  if (t.size() < 3 || !is(t, 0, f) || !is(t, 1, "(") || close_of(t, 1) != t.size() - 1) return std::nullopt;
  std::vector<Tokens> args;
  size_t from = 2;
  int depth = 0;
  for (size_t i = 2; i + 1 < t.size(); ++i) {
    if (is(t, i, "(") || is(t, i, "[")) ++depth;
    if (is(t, i, ")") || is(t, i, "]")) --depth;
    if (depth == 0 && is(t, i, ",")) {
      args.push_back(unwrapped(t.subspan(from, i - from)));
      from = i + 1;
    }
  }
  args.push_back(unwrapped(t.subspan(from, t.size() - 1 - from)));
  return args;
}

bool number_is(Tokens t, double value) {
  return t.size() == 1 && t[0].kind == Kind::number && std::strtod(std::string(t[0].text).c_str(), nullptr) == value;
}

// The reference clamps at 0 what the student leaves as it is: max(0.0, X), max(X, 0.0), clamp(X, 0.0, 1.0).
bool clamps(Tokens reference, Tokens student) {
  if (const auto args = call_of(reference, "max"); args && args->size() == 2)
    return (number_is((*args)[0], 0) && same((*args)[1], student)) || (same((*args)[0], student) && number_is((*args)[1], 0));
  if (const auto args = call_of(reference, "clamp"); args && args->size() == 3)
    return same((*args)[0], student) && number_is((*args)[1], 0) && number_is((*args)[2], 1);
  return false;
}

// `-X` where X (its parentheses aside) is `of`.
bool negates(Tokens t, Tokens of) { return is(t, 0, "-") && one_operand(t.subspan(1)) && same(unwrapped(t.subspan(1)), of); }

// `A - B` at the top level, as its two sides; none for anything else.
std::optional<std::pair<Tokens, Tokens>> difference_of(Tokens t) {
  std::optional<size_t> at;
  for (size_t i = 0; i < t.size(); ++i) {
    if (is(t, i, "(") || is(t, i, "[")) {
      i = close_of(t, i);
      continue;
    }
    if (t[i].kind != Kind::punctuation || t[i].text == ".") continue;
    const bool binary = i > 0 && (operand_token(t, i - 1) || is(t, i - 1, ")") || is(t, i - 1, "]"));
    if (t[i].text != "-" || !binary || at) return std::nullopt;
    at = i;
  }
  if (!at || *at + 1 >= t.size()) return std::nullopt;
  return std::pair{t.first(*at), t.subspan(*at + 1)};
}

// The call whose argument list holds token `at` of `t` at its top level: the name before the
// unclosed `(`, or "".
std::string_view enclosing_call(Tokens t, size_t at) {
  int depth = 0;
  for (size_t k = at; k-- > 0;) {
    if (is(t, k, ")")) ++depth;
    if (is(t, k, "(") && depth-- == 0) return k > 0 && t[k - 1].kind == Kind::identifier ? t[k - 1].text : std::string_view();
  }
  return {};
}

// One token for one, at the same place: a name, a number (a vec4's w), an operator.
std::optional<ValueDifference> one_token(Tokens a, size_t at, Tokens b, size_t b_at, std::string_view name) {
  const auto& mine = a[at];
  const auto& theirs = b[b_at];
  if (mine.kind == Kind::identifier && theirs.kind == Kind::identifier) return ValueDifference{RepairKind::name_replaced, std::string(mine.text), {}};
  if (mine.kind == Kind::number && theirs.kind == Kind::number) {
    const Tokens w = a.subspan(at, 1), their_w = b.subspan(b_at, 1);
    const bool last_argument = is(a, at - 1, ",") && is(a, at + 1, ")") && enclosing_call(a, at) == "vec4";
    if (last_argument && ((number_is(w, 0) && number_is(their_w, 1)) || (number_is(w, 1) && number_is(their_w, 0))))
      return ValueDifference{RepairKind::direction_w, std::string(name), number_is(their_w, 0) ? "0.0" : "1.0"};
    return ValueDifference{RepairKind::literal_refit, std::string(mine.text), {}};
  }
  const bool plus_minus = (mine.text == "+" || mine.text == "-") && (theirs.text == "+" || theirs.text == "-");
  const size_t right = at + 1;
  if (plus_minus && at > 0 && (operand_token(a, right) || is(a, right, "("))) {
    const size_t last = term_last(a, right);
    if (last < a.size()) return ValueDifference{RepairKind::operator_swapped, written(a.subspan(right, last - right + 1)), std::string(theirs.text)};
  }
  return std::nullopt;
}

// Tokens only one side has, between what the two share before and after: a sign, a factor, a
// term, a matrix.
std::optional<ValueDifference> one_side(Tokens a, Tokens extra_a, Tokens extra_b, size_t at) {
  // A sign: said of the operand it stands before (`vPosition` in normalize(-vPosition)).
  const auto operand_at = [&](size_t first) -> std::optional<std::string> {
    const size_t last = operand_last(a, first);
    if (last >= a.size()) return std::nullopt;
    return written(a.subspan(first, last - first + 1));
  };
  if (extra_a.empty() && extra_b.size() == 1 && is(extra_b, 0, "-"))
    if (auto operand = operand_at(at)) return ValueDifference{RepairKind::negation_added, *operand, {}};
  if (extra_b.empty() && extra_a.size() == 1 && is(extra_a, 0, "-"))
    if (auto operand = operand_at(at + 1)) return ValueDifference{RepairKind::negation_removed, *operand, {}};
  if (extra_a.empty() && extra_b.size() == 2 && extra_b[0].kind == Kind::identifier && is(extra_b, 1, "*"))
    if (auto operand = operand_at(at)) return ValueDifference{RepairKind::matrix_added, *operand, std::string(extra_b[0].text)};
  if (!extra_b.empty() || extra_a.size() < 2) return std::nullopt;
  const auto op = extra_a.front().text, trailing = extra_a.back().text;
  if (op == "*" && one_operand(extra_a.subspan(1))) return ValueDifference{RepairKind::factor_removed, written(extra_a.subspan(1)), {}};
  if (trailing == "*" && one_operand(extra_a.first(extra_a.size() - 1)))
    return ValueDifference{RepairKind::factor_removed, written(extra_a.first(extra_a.size() - 1)), {}};
  if ((op == "+" || op == "-") && one_operand(extra_a.subspan(1))) return ValueDifference{RepairKind::term_removed, written(extra_a), {}};
  return std::nullopt;
}

// A change of the whole of `a` into `b` a student makes as one edit: a normalize, a clamp at 0, a
// sign, a difference written the other way round. `subject` names what changes.
std::optional<ValueDifference> whole_change(Tokens a, Tokens b, const std::string& subject) {
  if (const auto args = call_of(b, "normalize"); args && args->size() == 1 && same((*args)[0], a)) return ValueDifference{RepairKind::normalised, subject, {}};
  if (const auto args = call_of(a, "normalize"); args && args->size() == 1 && same((*args)[0], b)) return ValueDifference{RepairKind::unnormalised, subject, {}};
  if (clamps(b, a)) return ValueDifference{RepairKind::clamped, written(a), {}};
  if (negates(b, a)) return ValueDifference{RepairKind::negation_added, subject, {}};
  if (negates(a, b)) return ValueDifference{RepairKind::negation_removed, subject, {}};
  // uLightPosition - vPosition written the other way round: the opposite direction.
  if (const auto mine = difference_of(a), theirs = difference_of(b);
      mine && theirs && same(mine->first, theirs->second) && same(mine->second, theirs->first))
    return ValueDifference{RepairKind::negation_added, subject, {}};
  return std::nullopt;
}

// `vec4(X.xyz, 0.0)` where the reference reads X as it is: the student gave X a w of their own (0
// or 1), where the render confirmed X's own w: the other one.
std::optional<ValueDifference> w_given(Tokens a, Tokens b) {
  const auto args = call_of(a, "vec4");
  if (!args || args->size() != 2 || !one_operand(b) || b.size() != 1) return std::nullopt;
  const Tokens xyz = (*args)[0], w = (*args)[1];
  if (xyz.size() != 3 || !same(xyz.first(1), b) || !is(xyz, 1, ".") || !is(xyz, 2, "xyz")) return std::nullopt;
  if (number_is(w, 0)) return ValueDifference{RepairKind::direction_w, std::string(b[0].text), "1.0"};
  if (number_is(w, 1)) return ValueDifference{RepairKind::direction_w, std::string(b[0].text), "0.0"};
  return std::nullopt;
}

// `M * vec4(X.xyz, 1.0)` where the reference reads `N * X`, M and N two matrices: the student gave
// X a w of their own and transformed it by another matrix. Said as the w, of the local it writes
// (`name`), with the homework's matrix: both changes are in the value the render confirmed.
std::optional<ValueDifference> matrix_and_w(Tokens a, Tokens b, std::string_view name) {
  if (a.size() < 3 || b.size() < 3 || a[0].kind != Kind::identifier || b[0].kind != Kind::identifier || a[0].text == b[0].text ||
      !is(a, 1, "*") || !is(b, 1, "*"))
    return std::nullopt;
  auto w = w_given(a.subspan(2), b.subspan(2));
  if (!w) return std::nullopt;
  w->subject = std::string(name);
  w->homework_matrix = std::string(b[0].text);
  return w;
}

}  // namespace

namespace {

// A sign changed inside normalize(X), X the whole argument: the direction itself has the wrong
// sign, said of the student's local ("`toEye`, the direction to the eye, has the wrong sign")
// rather than of what it normalises.
std::optional<ValueDifference> said_of_the_direction(std::optional<ValueDifference> d, Tokens a, std::string_view name) {
  if (!d || (d->said_as != RepairKind::negation_added && d->said_as != RepairKind::negation_removed)) return d;
  const auto args = call_of(a, "normalize");
  if (!args || args->size() != 1) return d;
  std::string argument = written((*args)[0]);
  if (argument.starts_with("-")) argument = argument.substr(argument.find_first_not_of("- "));
  if (argument == d->subject) d->subject = std::string(name);
  return d;
}

std::optional<ValueDifference> difference(Tokens a, Tokens b, std::string_view name) {
  if (auto whole = whole_change(a, b, std::string(name))) return whole;
  // Where the two share tokens before and after, the change is what lies between.
  size_t before = 0;
  while (before < a.size() && before < b.size() && a[before].text == b[before].text) ++before;
  size_t after = 0;
  while (after < a.size() - before && after < b.size() - before && a[a.size() - 1 - after].text == b[b.size() - 1 - after].text) ++after;
  const Tokens extra_a = a.subspan(before, a.size() - before - after), extra_b = b.subspan(before, b.size() - before - after);
  if (!extra_a.empty() && !extra_b.empty()) {
    if (auto part = whole_change(unwrapped(extra_a), unwrapped(extra_b), written(extra_a))) return part;
    if (auto w = w_given(extra_a, extra_b)) return w;
    if (auto w = matrix_and_w(extra_a, extra_b, name)) return w;
  }
  if (extra_a.size() == 1 && extra_b.size() == 1) return one_token(a, before, b, before, name);
  return one_side(a, extra_a, extra_b, before);
}

}  // namespace

std::optional<ValueDifference> value_difference(Tokens student, Tokens reference, std::string_view name) {
  const Tokens a = unwrapped(student), b = unwrapped(reference);
  if (a.empty() || b.empty() || same(a, b)) return std::nullopt;
  return said_of_the_direction(difference(a, b, name), a, name);
}

}  // namespace shadelab::repair
