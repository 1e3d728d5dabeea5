#include "repair/repair_edits.h"

#include <algorithm>
#include <map>
#include <tuple>

#include "repair/left_out_edits.h"
#include "repair/reference_edits.h"
#include "repair/stage_names.h"
#include "repair/stage_tokens.h"

namespace shadelab::repair {

namespace {

using Stage = StageTokens;

// `-X` for an operand, `-(X)` for anything longer.
std::string negated(const Stage& s, size_t first, size_t last) {
  const std::string text(s.text(first, last));
  return s.operand_last(first) == last ? "-" + text : "-(" + text + ")";
}

// vec3 L = X;  and  L = X;  for a vec3 L: normalise X, or negate it.
void vector_values(const Stage& s, const TypedNames& types, std::vector<RepairEdit>& out) {
  for (size_t i = 1; i + 2 < s.size(); ++i) {
    const bool declared = s.is(i - 1, "vec3") && s.identifier(i) && s.is(i + 1, "=");
    const auto type = types.find(s.t[i].text);
    const bool assigned = !declared && s.identifier(i) && s.is(i + 1, "=") && (s.is(i - 1, ";") || s.is(i - 1, "{") || s.is(i - 1, "}")) &&
                          type != types.end() && type->second == "vec3";
    if (!declared && !assigned) continue;
    const size_t first = i + 2, last = s.expression_last(first);
    if (last < first) continue;
    const std::string_view name = s.t[i].text, value = s.text(first, last);
    if (!(s.is(first, "normalize") && s.close_of(first + 1) == last))
      out.push_back(s.replace(RepairKind::normalised, first, last, "normalize(" + std::string(value) + ")", name));
    if (!s.is(first, "-")) out.push_back(s.replace(RepairKind::negation_added, first, last, negated(s, first, last), name));
  }
}

// Calls: normalize(X) -> X; dot(A, B) -> max(0.0, dot(A, B)) where nothing clamps it;
// vec4(n, 1.0) <-> vec4(n, 0.0); reflect(L, N) -> reflect(-L, N).
void calls(const Stage& s, std::vector<RepairEdit>& out) {
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    if (!s.identifier(i) || !s.is(i + 1, "(")) continue;
    const size_t close = s.close_of(i + 1);
    if (close >= s.size()) continue;
    const auto args = s.arguments(i + 1);
    const std::string_view name = s.t[i].text;
    if (name == "normalize" && args.size() == 1)
      out.push_back(s.replace(RepairKind::unnormalised, i, close, std::string(s.text(args[0].first, args[0].second)), s.text(i, close)));
    if (name == "dot" && !one_of(s.enclosing_call(i), {"max", "clamp"}))
      out.push_back(s.replace(RepairKind::clamped, i, close, "max(0.0, " + std::string(s.text(i, close)) + ")", s.text(i, close)));
    if (name == "vec4" && args.size() >= 2 && args.back().first == args.back().second && s.number(args.back().first)) {
      const std::string_view w = s.t[args.back().first].text;
      const bool one = one_of(w, {"1.0", "1.", "1"}), zero = one_of(w, {"0.0", "0.", "0"});
      if (one || zero) {
        RepairEdit e = s.replace(RepairKind::direction_w, args.back().first, args.back().first, zero ? "1.0" : "0.0",
                                 s.text(args[0].first, args[args.size() - 2].second));
        e.other = e.with;
        out.push_back(std::move(e));
      }
    }
    if (name == "reflect" && args.size() == 2 && !s.is(args[0].first, "-"))
      out.push_back(s.replace(RepairKind::negation_added, args[0].first, args[0].second, negated(s, args[0].first, args[0].second),
                              s.text(args[0].first, args[0].second)));
  }
}

// -X -> X; 0.5 * X -> X; X * 2.0 -> X; M * P -> P for a matrix M; X + vec3(0.0, 4.0, 0.0) -> X.
void operators(const Stage& s, const TypedNames& types, std::vector<RepairEdit>& out) {
  for (size_t i = 1; i + 1 < s.size(); ++i) {
    const std::string_view op = s.t[i].text;
    const bool unary = before_operand(s.t[i - 1].text);
    if (op == "-" && unary && (s.identifier(i + 1) || s.is(i + 1, "(") || s.number(i + 1))) {
      const size_t last = s.operand_last(i + 1);
      out.push_back(s.replace(RepairKind::negation_removed, i, last, std::string(s.text(i + 1, last)), s.text(i + 1, last)));
    }
    if (op == "*" && !unary) {
      const bool left_starts = i >= 2 && before_operand(s.t[i - 2].text);
      const auto type = types.find(s.t[i - 1].text);
      const bool matrix = type != types.end() && type->second.starts_with("mat");
      // A number's edit names the value it scales where that is one name (`2.0 * uAmbientColor`):
      // its words say the ambient colour is doubled, not that a number is somewhere.
      const auto scaled = [&](size_t at) {
        const bool one_name = s.identifier(at) && !s.is(at + 1, "(") && !s.is(at - 1, ".") && !s.is(at + 1, ".");
        return one_name ? std::string(s.t[at].text) : std::string();
      };
      if (left_starts && (s.number(i - 1) || (s.identifier(i - 1) && matrix))) {
        out.push_back(s.edit(RepairKind::factor_removed, s.begin(i - 1), s.begin(i + 1), "", i - 1, s.t[i - 1].text));
        if (s.number(i - 1) && !s.is(i + 2, "*")) out.back().other = scaled(i + 1);
      }
      if (s.number(i + 1) && (i + 2 >= s.size() || one_of(s.t[i + 2].text, {";", ")", ",", "+", "-"}))) {
        out.push_back(s.edit(RepairKind::factor_removed, s.end(i - 1), s.end(i + 1), "", i + 1, s.t[i + 1].text));
        if (!s.is(i - 2, "*")) out.back().other = scaled(i - 1);
      }
    }
    if ((op == "+" || op == "-") && !unary) {
      // The other operator: the right operand (after `=` for += and -=) is what it adds or subtracts.
      const size_t right = s.is(i + 1, "=") ? i + 2 : i + 1;
      if (right < s.size() && !s.is(right, "=")) {
        RepairEdit e = s.replace(RepairKind::operator_swapped, i, i, op == "+" ? "-" : "+", s.text(right, s.expression_last(right)));
        e.other = e.with;
        out.push_back(std::move(e));
      }
      size_t last = i + 1;
      if (s.identifier(i + 1) && s.t[i + 1].text.starts_with("vec") && s.is(i + 2, "(")) {
        last = s.close_of(i + 2);
        bool literal = last < s.size();
        for (size_t k = i + 3; literal && k < last; ++k) literal = s.number(k) || s.is(k, ",") || s.is(k, "-");
        if (!literal) continue;
      } else if (!s.number(i + 1)) {
        continue;
      }
      out.push_back(s.edit(RepairKind::term_removed, s.end(i - 1), s.end(last), "", i, s.text(i, last)));
    }
  }
}

// color.bgra -> color: a swizzle of three or four channels out of their order.
void swizzles(const Stage& s, std::vector<RepairEdit>& out) {
  for (size_t i = 1; i + 1 < s.size(); ++i) {
    if (!s.is(i, ".") || !s.identifier(i + 1) || (!s.identifier(i - 1) && !s.is(i - 1, ")"))) continue;
    const std::string_view field = s.t[i + 1].text;
    if (field.size() < 3 || field.size() > 4) continue;
    const bool colour = field.find_first_not_of("rgba") == std::string_view::npos, place = field.find_first_not_of("xyzw") == std::string_view::npos;
    if ((!colour && !place) || std::string_view(colour ? "rgba" : "xyzw").starts_with(field)) continue;
    size_t first = i - 1;
    if (s.is(first, ")")) {
      for (size_t k = first; k-- > 0;)
        if (s.is(k, "(") && s.close_of(k) == first) {
          first = k > 0 && s.identifier(k - 1) ? k - 1 : k;
          break;
        }
    }
    out.push_back(s.edit(RepairKind::swizzle_removed, s.begin(i), s.end(i + 1), "", i, s.text(first, i + 1)));
  }
}

// A value a stage can read by name: a uniform or an input (from the start), or a local, from its
// declaration on (blocks are not scopes here: a candidate that does not compile is passed over).
struct Readable {
  std::string type;
  size_t from = 0;  // the first token that may read it
};

std::map<std::string, Readable, std::less<>> readable_names(const Stage& s) {
  std::map<std::string, Readable, std::less<>> names;
  for (auto& [name, type] : read_only_names(s)) names.emplace(name, Readable{type, 0});
  for (size_t i = 1; i + 1 < s.size(); ++i)
    if (one_of(s.t[i - 1].text, {"float", "vec3", "vec4"}) && s.identifier(i) && s.is(i + 1, "=") && !s.is(i + 2, "="))
      names.emplace(std::string(s.t[i].text), Readable{std::string(s.t[i - 1].text), i + 2});
  return names;
}

// A uniform, an input or a local read where another of its type was meant.
void names(const Stage& s, std::vector<RepairEdit>& out) {
  const auto readable = readable_names(s);
  for (size_t i = 0; i < s.size(); ++i) {
    const auto found = s.identifier(i) ? readable.find(s.t[i].text) : readable.end();
    if (found == readable.end() || !read_at(s, i) || i < found->second.from) continue;
    for (const auto& [other, value] : readable) {
      if (other == found->first || value.type != found->second.type || i < value.from) continue;
      RepairEdit e = s.replace(RepairKind::name_replaced, i, i, other, found->first);
      e.other = other;
      out.push_back(std::move(e));
    }
  }
}

// A matrix uniform missing from a product: put before an input vec4 (aVertexNormal) or before a
// matrix that starts a product (uMeshToWorldMatrix * P).
void matrices(const Stage& s, const TypedNames& types, std::vector<RepairEdit>& out) {
  const auto inputs = read_only_names(s);
  std::vector<std::string> matrices;
  for (const auto& [name, type] : inputs)
    if (type == "mat4") matrices.push_back(name);
  for (size_t i = 1; i < s.size(); ++i) {
    if (!s.identifier(i) || !read_at(s, i)) continue;
    const auto type = types.find(s.t[i].text);
    const bool matrix = type != types.end() && type->second == "mat4" && before_operand(s.t[i - 1].text) && s.is(i + 1, "*");
    const auto input = inputs.find(s.t[i].text);
    const bool vector = input != inputs.end() && input->second == "vec4" && (s.is(i - 1, "*") || before_operand(s.t[i - 1].text));
    if (!matrix && !vector) continue;
    for (const auto& m : matrices) {
      if (m == s.t[i].text || (i >= 2 && s.is(i - 1, "*") && s.t[i - 2].text == m)) continue;
      RepairEdit e = s.edit(RepairKind::matrix_added, s.begin(i), s.begin(i), m + " * ", i, s.text(i, s.operand_last(i)));
      e.other = m;
      out.push_back(std::move(e));
    }
  }
}

// Two arguments in the wrong order: reflect(N, -L) -> reflect(-L, N), pow(a, x) -> pow(x, a). Not
// where the order cannot matter (dot, max, min, distance), in a constructor or in a declaration.
void argument_orders(const Stage& s, std::vector<RepairEdit>& out) {
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    if (!s.identifier(i) || !s.is(i + 1, "(") || (i > 0 && s.identifier(i - 1) && !s.is(i - 1, "return"))) continue;
    const std::string_view name = s.t[i].text;
    if (one_of(name, {"dot", "max", "min", "distance", "float", "int", "uint", "bool"}) || name.starts_with("vec") ||
        name.starts_with("ivec") || name.starts_with("uvec") || name.starts_with("bvec") || name.starts_with("mat"))
      continue;
    const size_t close = s.close_of(i + 1);
    if (close >= s.size()) continue;
    const auto args = s.arguments(i + 1);
    if (args.size() != 2) continue;
    const auto [first, second] = std::pair(args[0], args[1]);
    const std::string_view a = s.text(first.first, first.second), b = s.text(second.first, second.second);
    if (a == b) continue;
    const std::string_view between = s.glsl.substr(s.end(first.second), s.begin(second.first) - s.end(first.second));
    RepairEdit e = s.replace(RepairKind::arguments_swapped, first.first, second.second, std::string(b) + std::string(between) + std::string(a),
                             s.text(i, close));
    e.nodes = 2;
    out.push_back(std::move(e));
  }
}

// The `flat` token of each varying a stage declares flat (`flat out vec3 vNormal;`, `flat in
// highp vec3 vNormal;`), by name.
std::map<std::string, size_t, std::less<>> flat_varyings(const Stage& s, std::string_view direction) {
  std::map<std::string, size_t, std::less<>> at;
  for (size_t i = 0; i + 3 < s.size(); ++i) {
    if (!s.is(i, "flat") || !s.is(i + 1, direction)) continue;
    size_t k = i + 2;
    if (one_of(s.t[k].text, {"lowp", "mediump", "highp"})) ++k;
    if (s.identifier(k) && s.identifier(k + 1) && s.is(k + 2, ";")) at.emplace(std::string(s.t[k + 1].text), i);
  }
  return at;
}

// A varying flat in both stages -> interpolated in both: one edit, said at the vertex stage's line.
void flat_removals(const Stage& v, const Stage& f, std::vector<RepairEdit>& out) {
  const auto inputs = flat_varyings(f, "in");
  for (const auto& [name, i] : flat_varyings(v, "out")) {
    const auto in = inputs.find(name);
    if (in == inputs.end()) continue;
    RepairEdit e = v.edit(RepairKind::flat_removed, v.begin(i), v.begin(i + 1), "", i, name);
    e.other_stage = OtherStageSpan{f.begin(in->second), f.begin(in->second + 1), ""};
    out.push_back(std::move(e));
  }
}

}  // namespace

std::vector<RepairEdit> repair_edits(const Stage& s) {
  const auto types = declared_types(s);
  std::vector<RepairEdit> out;
  vector_values(s, types, out);
  calls(s, out);
  operators(s, types, out);
  matrices(s, types, out);
  names(s, out);
  argument_orders(s, out);
  swizzles(s, out);
  std::stable_sort(out.begin(), out.end(), smaller);
  return out;
}

ProgramEdits program_edits(const ProgramReading& student) {
  ProgramEdits out;
  for (const shader::Stage stage : {shader::Stage::vertex, shader::Stage::fragment}) {
    const StageReading& s = student[stage];
    std::vector<RepairEdit> edits = repair_edits(s.student);
    if (!s.theirs.glsl.empty()) {
      for (auto& e : reference_edits(s.student, s.theirs)) edits.push_back(std::move(e));
      for (auto& e : left_out_edits(s.student, s.theirs)) edits.push_back(std::move(e));
    }
    for (auto& e : edits) {
      // A line the student wrote as the reference writes it (their names for its locals aside) is
      // right as it is: an edit there that makes up for a mistake elsewhere would name a change
      // the student never made.
      if (!inserts_statement(e.kind) && !e.edits_aligned_line && s.written_as_theirs(e)) continue;
      e.reads_as_reference = inserts_statement(e.kind) || s.reads_as_theirs_after(e);
      (s.liveness.dead(e.begin) ? out.dead : out.live).push_back(std::move(e));
    }
  }
  std::vector<RepairEdit> flat;
  flat_removals(student.vertex.student, student.fragment.student, flat);
  for (auto& e : flat) {
    const RepairEdit in{shader::Stage::fragment, e.kind, e.other_stage->begin, e.other_stage->end, e.other_stage->with};
    e.reads_as_reference = student.vertex.reads_as_theirs_after(e) && student.fragment.reads_as_theirs_after(in);
    out.live.push_back(std::move(e));
  }
  std::stable_sort(out.live.begin(), out.live.end(), smaller);
  std::stable_sort(out.dead.begin(), out.dead.end(), smaller);
  return out;
}

std::vector<RepairEdit> program_repair_edits(const StagePair& student, const StagePair& reference, Liveness which) {
  ProgramEdits edits = program_edits(ProgramReading(student, reference));
  return std::move(which == Liveness::live ? edits.live : edits.dead);
}

}  // namespace shadelab::repair
