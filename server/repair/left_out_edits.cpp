#include "repair/left_out_edits.h"

#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include "repair/stage_names.h"
#include "repair/student_names.h"

namespace shadelab::repair {

namespace {

using Stage = StageTokens;

// The first token of the operand whose last token is `last`: `max(...)`, `(a + b)`, `color.rgb`.
size_t operand_first(const Stage& s, size_t last) {
  size_t i = last;
  if (s.is(i, ")")) {
    for (int depth = 0;; --i) {
      depth += s.is(i, ")") - s.is(i, "(");
      if (depth == 0 || i == 0) break;
    }
    if (i > 0 && s.identifier(i - 1)) --i;
  }
  return i >= 2 && s.is(i - 1, ".") ? operand_first(s, i - 2) : i;
}

// The product the operand at `i` is a factor of, its first and last token: `a * b * max(...)`.
std::pair<size_t, size_t> product_of(const Stage& s, size_t i) {
  size_t first = i, last = s.operand_last(i);
  while (last + 2 < s.size() && s.is(last + 1, "*")) last = s.operand_last(last + 2);
  while (first >= 2 && s.is(first - 1, "*")) first = operand_first(s, first - 2);
  return {first, last};
}

// The uniforms a product multiplies, each a factor of its own: {uDiffuseColor, uLightColor} in
// `uDiffuseColor * uLightColor * max(...)`; and the last of them.
struct UniformFactors {
  std::set<std::string, std::less<>> names;
  size_t last = 0;
};

// Each product of a stage that multiplies a uniform, once.
std::vector<UniformFactors> uniform_products(const Stage& s) {
  const TypedNames uniforms = read_only_names(s);
  std::vector<UniformFactors> out;
  std::set<std::pair<size_t, size_t>> seen;
  for (size_t i = 0; i < s.size(); ++i) {
    if (!s.identifier(i) || !uniforms.contains(s.t[i].text) || !read_at(s, i)) continue;
    const auto [first, last] = product_of(s, i);
    if (!seen.insert({first, last}).second) continue;
    UniformFactors f;
    for (size_t k = first; k <= last; ++k)
      if (s.identifier(k) && uniforms.contains(s.t[k].text) && (k == first || s.is(k - 1, "*")) && (k == last || s.is(k + 1, "*"))) {
        f.names.emplace(s.t[k].text);
        f.last = k;
      }
    if (!f.names.empty()) out.push_back(std::move(f));
  }
  return out;
}

// uDiffuseColor * max(...)  ->  uDiffuseColor * uLightColor * max(...): a product of the
// student's whose uniforms are all but one of a product of the reference's, the one put after
// the student's last.
void factors_added(const Stage& s, const Stage& r, std::vector<RepairEdit>& out) {
  const TypedNames uniforms = read_only_names(s);
  const auto theirs = uniform_products(r);
  for (const auto& own : uniform_products(s)) {
    std::set<std::string> missing;
    for (const auto& product : theirs) {
      if (product.names.size() != own.names.size() + 1 ||
          !std::includes(product.names.begin(), product.names.end(), own.names.begin(), own.names.end()))
        continue;
      for (const auto& name : product.names)
        if (!own.names.contains(name) && uniforms.contains(name)) missing.insert(name);
    }
    for (const auto& factor : missing) {
      RepairEdit e = s.edit(RepairKind::factor_added, s.end(own.last), s.end(own.last), " * " + factor, own.last, s.t[own.last].text);
      e.other = factor;
      out.push_back(std::move(e));
    }
  }
}

// A float the student computes and never reads (`float lit = max(sign(dot(n, l)), 0.0);`),
// multiplied into each power after it, where the reference guards its power: the student's own
// guard, written and then left out of the product.
void unused_factors(const Stage& s, const Stage& r, std::vector<RepairEdit>& out) {
  if (calls_of(r, "pow") == 0 || conditions_of(r).empty()) return;
  for (size_t i = 1; i + 1 < s.size(); ++i) {
    if (!s.is(i - 1, "float") || !s.identifier(i) || !s.is(i + 1, "=") || reads(s, s.t[i].text)) continue;
    for (size_t k = statement_end(s, i); k + 1 < s.size(); ++k) {
      if (!s.is(k, "pow") || !s.is(k + 1, "(") || s.close_of(k + 1) >= s.size()) continue;
      RepairEdit e = s.edit(RepairKind::factor_added, s.begin(k), s.begin(k), std::string(s.t[i].text) + " * ", k, s.text(k, s.close_of(k + 1)));
      e.other = std::string(s.t[i].text);
      out.push_back(std::move(e));
    }
  }
}

// The uniforms the reference adds as a term of their own: `uAmbientColor + D`, `D + uAmbientColor`.
std::set<std::string> uniform_terms(const Stage& r) {
  const TypedNames uniforms = read_only_names(r);
  std::set<std::string> out;
  for (size_t i = 1; i + 1 < r.size(); ++i)
    if (r.identifier(i) && uniforms.contains(r.t[i].text) &&
        ((r.is(i - 1, "=") && r.is(i + 1, "+")) || (r.is(i - 1, "+") && one_of(r.t[i + 1].text, {"+", ";"}))))
      out.emplace(r.t[i].text);
  return out;
}

// The type each of a stage's outputs is declared with: `out vec4 fragColor;`.
TypedNames output_types(const Stage& s) {
  TypedNames out;
  for (size_t i = 0; i + 3 < s.size(); ++i) {
    if (!s.is(i, "out")) continue;
    size_t k = i + 1;
    if (one_of(s.t[k].text, {"lowp", "mediump", "highp"})) ++k;
    if (s.identifier(k) && s.identifier(k + 1) && s.is(k + 2, ";")) out.emplace(std::string(s.t[k + 1].text), std::string(s.t[k].text));
  }
  return out;
}

// color = D;  ->  color = uAmbientColor + D;  for a uniform the reference adds as a term and the
// student's stage never reads, at each whole write of a value of its type.
void terms_added(const Stage& s, const Stage& r, std::vector<RepairEdit>& out) {
  const TypedNames uniforms = read_only_names(s);
  TypedNames types = declared_types(s);
  types.merge(output_types(s));
  for (const auto& term : uniform_terms(r)) {
    const auto uniform = uniforms.find(term);
    if (uniform == uniforms.end() || reads(s, term)) continue;
    for (size_t i = 1; i + 2 < s.size(); ++i) {
      if (!s.identifier(i) || !s.is(i + 1, "=") || s.is(i + 2, "=")) continue;
      if (!statement_start(s, i) && !(statement_start(s, i - 1) && s.identifier(i - 1))) continue;  // name = X, or TYPE name = X
      const auto type = types.find(s.t[i].text);
      if (type == types.end() || type->second != uniform->second) continue;
      RepairEdit e = s.edit(RepairKind::term_added, s.begin(i + 2), s.begin(i + 2), term + " + ", i + 2, term);
      e.other = std::string(s.t[i].text);
      out.push_back(std::move(e));
    }
  }
}

// The exponent the reference raises a cosine to, as the student's stage can write it: the
// reference's name where the student's stage declares it too, else the number the reference
// declares it with, or the reference's number.
std::optional<std::string> exponent_text(const Stage& s, const Stage& r, size_t first, size_t last) {
  if (first != last) return std::nullopt;
  if (r.number(first)) return std::string(r.t[first].text);
  if (!r.identifier(first)) return std::nullopt;
  const std::string_view name = r.t[first].text;
  if (declared_types(s).contains(name) || read_only_names(s).contains(name)) return std::string(name);
  for (size_t k = 1; k + 3 < r.size(); ++k)
    if (r.is(k, name) && r.identifier(k - 1) && r.is(k + 1, "=") && r.number(k + 2) && r.is(k + 3, ";")) return std::string(r.t[k + 2].text);
  return std::nullopt;
}

// max(dot(V, R), 0.0)  ->  pow(max(dot(V, R), 0.0), specularAlpha), where the student's stage
// calls pow less often than the reference's.
void exponents_added(const Stage& s, const Stage& r, std::vector<RepairEdit>& out) {
  if (calls_of(r, "pow") <= calls_of(s, "pow")) return;
  std::set<std::string> exponents;
  for (size_t i = 0; i + 1 < r.size(); ++i) {
    if (!r.is(i, "pow") || !r.is(i + 1, "(")) continue;
    const auto args = r.arguments(i + 1);
    if (args.size() != 2) continue;
    if (auto x = exponent_text(s, r, args[1].first, args[1].second)) exponents.insert(std::move(*x));
  }
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    if (!one_of(s.t[i].text, {"max", "clamp"}) || !s.is(i + 1, "(") || s.enclosing_call(i) == "pow") continue;
    const size_t close = s.close_of(i + 1);
    if (close >= s.size() || !has_token(s, "dot", i, close)) continue;
    for (const auto& x : exponents) {
      RepairEdit e = s.replace(RepairKind::exponent_added, i, close, "pow(" + std::string(s.text(i, close)) + ", " + x + ")", s.text(i, close));
      e.other = x;
      out.push_back(std::move(e));
    }
  }
}

// What a guard added around the block at `open` guards: the first name the block adds to
// (`color += ...`), else the first it writes.
std::string guarded_name(const Stage& s, size_t open) {
  std::string first;
  int depth = 0;
  for (size_t i = open; i + 2 < s.size(); ++i) {
    if (s.is(i, "{")) ++depth;
    if (s.is(i, "}") && --depth == 0) break;
    if (!s.identifier(i) || !statement_start(s, i)) continue;
    const size_t name = s.identifier(i + 1) ? i + 1 : i;
    if (s.is(name + 1, "+") && s.is(name + 2, "=")) return std::string(s.t[name].text);
    if (first.empty() && s.is(name + 1, "=")) first = std::string(s.t[name].text);
  }
  return first;
}

// In a helper whose value is a power (`return ... pow(...);`): `if (!(dot(n, l) > 0.0)) { return
// vec4(0.0); }` before its first statement that reads a parameter, the early return students
// write for the guard.
void helper_guards(const Stage& s, const std::string& condition, std::vector<RepairEdit>& out) {
  for (const Helper& h : helpers_of(s)) {
    if (!has_token(s, "pow", h.open, h.close) || !has_token(s, "return", h.open, h.close)) continue;
    std::set<std::string_view> params;
    for (size_t k = h.params_first; k <= h.params_last; ++k)
      if (s.identifier(k) && (k == h.params_last || s.is(k + 1, ","))) params.insert(s.t[k].text);
    for (size_t k = h.open + 1; k < h.close; ++k) {
      if (!statement_start(s, k)) continue;
      bool reads_param = false;
      for (size_t j = k; j < statement_end(s, k) && !reads_param; ++j) reads_param = s.identifier(j) && params.contains(s.t[j].text);
      if (!reads_param) continue;
      RepairEdit e = s.edit(RepairKind::guard_added, s.begin(k), s.begin(k),
                            "if (!(" + condition + ")) { return " + std::string(h.type) + "(0.0); } ", k, s.t[h.params_first - 2].text);
      e.other = condition;
      e.edits_aligned_line = true;
      out.push_back(std::move(e));
      break;
    }
  }
}

// { ... }  ->  if (dot(N, L) > 0.0) { ... };  x = pow(...);  ->  if (...) { x = pow(...); }: the
// reference's condition in the student's names, where the student's stage tests fewer conditions.
void guards_added(const Stage& s, const Stage& r, std::vector<RepairEdit>& out) {
  const auto theirs = conditions_of(r);
  if (conditions_of(s).size() >= theirs.size()) return;
  const auto names = student_names(s, r);
  for (const auto& [first, last] : theirs) {
    const auto condition = in_student_names(s, r, first, last, names);
    if (!condition) continue;
    helper_guards(s, *condition, out);
    bool block_guarded = false;
    for (size_t i = 1; i + 2 < s.size(); ++i) {
      if (s.is(i, "{") && statement_start(s, i) && main_of(s, i)) {
        block_guarded = true;
        RepairEdit e = s.replace(RepairKind::guard_added, i, i, "if (" + *condition + ") {", guarded_name(s, i));
        e.other = *condition;
        out.push_back(std::move(e));
      }
      if (s.identifier(i) && statement_start(s, i) && s.is(i + 1, "=") && !s.is(i + 2, "=")) {
        const size_t end = statement_end(s, i);
        if (end >= s.size() || !has_token(s, "pow", i, end)) continue;
        RepairEdit e = s.replace(RepairKind::guard_added, i, end, "if (" + *condition + ") { " + std::string(s.text(i, end)) + " }", s.t[i].text);
        e.other = *condition;
        out.push_back(std::move(e));
      }
      // A declaration cannot go inside an `if` (its name would end with the block): its value
      // takes the guard, `float ks = cosTheta > 0.0 ? pow(...) : 0.0;`, where no bare block
      // before it could take the `if` instead.
      if (!block_guarded && s.identifier(i) && s.identifier(i - 1) && statement_start(s, i - 1) && s.is(i + 1, "=") && !s.is(i + 2, "=")) {
        const size_t end = statement_end(s, i);
        const std::string_view type = s.t[i - 1].text;
        if (end >= s.size() || end == i + 2 || !has_token(s, "pow", i, end) || !(type == "float" || type.starts_with("vec"))) continue;
        const std::string zero = type == "float" ? "0.0" : std::string(type) + "(0.0)";
        RepairEdit e = s.replace(RepairKind::guard_added, i + 2, end - 1, *condition + " ? " + std::string(s.text(i + 2, end - 1)) + " : " + zero,
                                 s.t[i].text);
        e.other = *condition;
        out.push_back(std::move(e));
      }
    }
  }
}

// Each local of the student's the reference has too: by the reference's name, the student's.
std::map<std::string, std::string, std::less<>> shared_locals(const Stage& s, const Stage& r) {
  auto out = student_names(s, r);
  const TypedNames theirs = declared_types(r), inputs = read_only_names(s);
  for (const auto& [name, type] : declared_types(s))
    if (theirs.contains(name) && !inputs.contains(name)) out.emplace(name, name);
  return out;
}

bool clamped_at(const Stage& s, size_t i) { return one_of(s.enclosing_call(i), {"max", "clamp"}); }

// The last statement writing `name` whole (declared or assigned; with `updates`, `+=` and the
// like too): the token of the name, or size().
size_t last_write(const Stage& s, std::string_view name, bool updates) {
  size_t at = s.size();
  for (size_t i = 1; i + 2 < s.size(); ++i) {
    if (!s.is(i, name) || !(statement_start(s, i) || (statement_start(s, i - 1) && s.identifier(i - 1)))) continue;
    const bool assigned = s.is(i + 1, "=") && !s.is(i + 2, "=");
    const bool updated = updates && one_of(s.t[i + 1].text, {"+", "-", "*"}) && s.is(i + 2, "=");
    if (assigned || updated) at = i;
  }
  return at;
}

// float diff = dot(N, L);  ->  float diff = max(0.0, dot(N, L));  where the student reads the
// local bare in a product and the reference reads its counterpart clamped (`max(0.0, NdotL)`):
// the student's line reads as the reference's `float NdotL = dot(N, L);`, and is edited all the
// same, since the student uses its value where the reference clamps it.
void clamps_added(const Stage& s, const Stage& r, std::vector<RepairEdit>& out) {
  // Each shared local, and each copy the student makes of one (`float kd = cosTheta;`, cosTheta
  // the reference's NdotL): the copy is what they read where the reference reads NdotL clamped.
  std::vector<std::pair<std::string, std::string>> shared;
  for (const auto& [theirs, own] : shared_locals(s, r)) {
    shared.emplace_back(theirs, own);
    for (size_t k = 2; k + 2 < s.size(); ++k)
      if (s.identifier(k - 1) && s.identifier(k) && s.is(k + 1, "=") && s.is(k + 2, own) && s.is(k + 3, ";") && s.t[k].text != own)
        shared.emplace_back(theirs, std::string(s.t[k].text));
  }
  for (const auto& [theirs, own] : shared) {
    bool clamped_there = false, bare_here = false;
    for (size_t k = 0; k < r.size(); ++k) clamped_there = clamped_there || (r.is(k, theirs) && read_at(r, k) && clamped_at(r, k));
    for (size_t k = 1; k + 1 < s.size(); ++k)
      bare_here = bare_here || (s.is(k, own) && read_at(s, k) && !clamped_at(s, k) && (s.is(k - 1, "*") || s.is(k + 1, "*")));
    const size_t written = last_write(s, own, false);
    if (!clamped_there || !bare_here || written >= s.size() || one_of(s.t[written + 2].text, {"max", "clamp"})) continue;
    const size_t first = written + 2, last = s.expression_last(first);
    if (last < first) continue;
    RepairEdit e = s.replace(RepairKind::clamped, first, last, "max(0.0, " + std::string(s.text(first, last)) + ")", own);
    e.edits_aligned_line = true;
    out.push_back(std::move(e));
  }
}

// The names tokens `first`..`last` read (calls among them), a reference's each written in the
// student's name for it where `names` has one.
std::set<std::string> names_read(const Stage& st, size_t first, size_t last, const NameMap& names = {}) {
  std::set<std::string> out;
  for (size_t k = first; k <= last && k < st.size(); ++k) {
    if (!st.identifier(k)) continue;
    const auto own = names.find(st.t[k].text);
    out.insert(own != names.end() ? own->second : std::string(st.t[k].text));
  }
  return out;
}

// The call whose argument token `i` is (`pow` for the `max` in `pow(max(...), a)`): its name's
// token, or size().
size_t enclosing_call_at(const Stage& st, size_t i) {
  int depth = 0;
  for (size_t k = i; k-- > 0;) {
    if (st.is(k, ")")) ++depth;
    if (st.is(k, "(") && depth-- == 0) return k > 0 && st.identifier(k - 1) ? k - 1 : st.size();
  }
  return st.size();
}

// The term the reference's call at `k` is in (`uSpecularColor * uLightColor * pow(...)`), with
// `name` in place of the call: the uniforms multiplied before and after it; none for a bare call.
std::optional<std::string> term_at(const Stage& r, size_t k, const std::string& name, const TypedNames& uniforms) {
  size_t first = k, last = r.close_of(k + 1);
  while (first >= 2 && r.is(first - 1, "*") && r.identifier(first - 2) && uniforms.contains(r.t[first - 2].text)) first -= 2;
  while (last + 2 < r.size() && r.is(last + 1, "*") && r.identifier(last + 2) && uniforms.contains(r.t[last + 2].text) && !r.is(last + 3, "("))
    last += 2;
  if (first == k && last == r.close_of(k + 1)) return std::nullopt;  // a bare call: no term of its own
  std::string term = first < k ? std::string(r.text(first, k - 1)) + " " : std::string();
  term += name;
  if (last > r.close_of(k + 1)) term += " " + std::string(r.text(r.close_of(k + 1) + 1, last));
  return term;
}

// The reference's term that calls `call` (`uSpecularColor * uLightColor * pow(...)`), with `name`
// in place of the call. Of the reference's calls of that name, first the one that reads what the
// student's call reads (`reads`, in the student's names): the student's `max(dot(R, V), 0.0)` is
// the specular term's `max(0.0, dot(V, R))`, not the diffuse term's `max(0.0, NdotL)`; where that
// one is an argument of another call (the `max` inside `pow`), the term of the call it is inside,
// with `name` in that call's place: the student left the outer call out too. Else the first call
// of that name that is a term.
std::optional<std::string> term_with(const Stage& r, std::string_view call, const std::string& name, const TypedNames& uniforms,
                                     const std::set<std::string>& reads = {}, const NameMap& names = {}) {
  for (size_t k = 2; k + 1 < r.size() && !reads.empty(); ++k) {
    if (!r.is(k, call) || !r.is(k + 1, "(") || names_read(r, k, r.close_of(k + 1), names) != reads) continue;
    if (auto term = term_at(r, k, name, uniforms)) return term;
    const size_t outer = enclosing_call_at(r, k);
    if (outer < r.size())
      if (auto term = term_at(r, outer, name, uniforms)) return term;
  }
  for (size_t k = 2; k + 1 < r.size(); ++k)
    if (r.is(k, call) && r.is(k + 1, "("))
      if (auto term = term_at(r, k, name, uniforms)) return term;
  return std::nullopt;
}

// float spec = pow(...); never read  ->  ...; color += uSpecularColor * uLightColor * spec;  the
// reference's term that calls what the student's unread value calls, with that value in its
// place, added to what the student accumulates the colour in, after both are written. A colour
// term computed into a local of its own and never read (`vec4 ambient = uAmbientColor;`) is
// added as it is.
void values_added(const Stage& s, const Stage& r, std::vector<RepairEdit>& out) {
  const TypedNames uniforms = read_only_names(s);
  const NameMap names = student_names(s, r);
  TypedNames targets = output_types(s);
  for (const auto& [theirs, own] : shared_locals(s, r))
    if (declared_types(r).at(theirs) == "vec4") targets.emplace(own, "vec4");
  for (size_t i = 1; i + 1 < s.size(); ++i) {
    const bool colour = s.is(i - 1, "vec4");
    if (!(colour || s.is(i - 1, "float")) || !s.identifier(i) || !s.is(i + 1, "=") || reads(s, s.t[i].text)) continue;
    const std::string name(s.t[i].text);
    const size_t written = last_write(s, name, false);
    if (written >= s.size() || !main_of(s, written)) continue;
    std::optional<std::string> term;
    if (colour) term = name;
    for (size_t k = written + 2; k + 1 < statement_end(s, written) && !term; ++k)
      if (s.identifier(k) && s.is(k + 1, "(")) term = term_with(r, s.t[k].text, name, uniforms, names_read(s, k, s.close_of(k + 1)), names);
    if (!term) continue;
    for (const auto& [target, type] : targets) {
      const size_t target_written = last_write(s, target, true);
      if (target_written >= s.size()) continue;
      const size_t after = statement_end(s, std::max(written, target_written));
      if (after >= s.size()) continue;
      RepairEdit e = s.edit(RepairKind::value_added, s.end(after), s.end(after), " " + target + " += " + *term + ";", after, name);
      e.other = *term;
      out.push_back(std::move(e));
    }
  }
}

// vec4 specularTerm(vec3 n, vec3 l, vec3 v) { ... pow(...) ... } never called  ->  fragColor = ...;
// fragColor += specularTerm(n, l, v);  a helper computing what a term of the reference computes,
// called with main's locals of its parameters' names, added to an output after its last write.
void helpers_added(const Stage& s, const Stage& r, std::vector<RepairEdit>& out) {
  const TypedNames uniforms = read_only_names(s), outputs = output_types(s);
  for (const Helper& h : helpers_of(s)) {
    const std::string_view name = s.t[h.params_first - 2].text;
    if (calls_of(s, name) != 1 || !has_token(s, "pow", h.open, h.close) || !term_with(r, "pow", "x", uniforms)) continue;
    std::vector<std::string> params;
    for (size_t k = h.params_first; k <= h.params_last; ++k)
      if (s.identifier(k) && (k == h.params_last || s.is(k + 1, ","))) params.emplace_back(s.t[k].text);
    bool in_main = true;
    for (const auto& p : params) {
      bool declared = false;
      for (size_t k = main_start(s); k + 1 < s.size() && !declared; ++k) declared = s.is(k, p) && s.identifier(k - 1) && s.is(k + 1, "=");
      in_main = in_main && declared;
    }
    if (!in_main) continue;
    std::string call = std::string(name) + "(";
    for (size_t k = 0; k < params.size(); ++k) call += (k ? ", " : "") + params[k];
    call += ")";
    for (const auto& [target, type] : outputs) {
      const size_t written = last_write(s, target, true);
      if (type != h.type || written >= s.size() || !main_of(s, written)) continue;
      const size_t after = statement_end(s, written);
      RepairEdit e = s.edit(RepairKind::value_added, s.end(after), s.end(after), " " + target + " += " + call + ";", after, name);
      e.other = call;
      out.push_back(std::move(e));
    }
  }
}

}  // namespace

std::vector<RepairEdit> left_out_edits(const StageTokens& s, const StageTokens& r) {
  std::vector<RepairEdit> out;
  if (r.glsl.empty()) return out;
  factors_added(s, r, out);
  unused_factors(s, r, out);
  terms_added(s, r, out);
  exponents_added(s, r, out);
  guards_added(s, r, out);
  clamps_added(s, r, out);
  values_added(s, r, out);
  helpers_added(s, r, out);
  return out;
}

}  // namespace shadelab::repair
