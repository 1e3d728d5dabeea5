#include "repair/value_probes.h"

#include <algorithm>
#include <map>
#include <set>
#include <utility>

#include "repair/program_reading.h"
#include "repair/stage_names.h"

namespace shadelab::repair {

namespace {

// Every value as a vec4 whose alpha 2 marks a pixel the probe ran at (the float target clears to
// alpha 1, a fragment whose probe did not run writes 0).
constexpr std::string_view kValueOf =
    "highp vec4 valueprobe_v(highp float x) { return vec4(x, x, x, 2.0); } "
    "highp vec4 valueprobe_v(highp vec2 x) { return vec4(x, 0.0, 2.0); } "
    "highp vec4 valueprobe_v(highp vec3 x) { return vec4(x, 2.0); } "
    "highp vec4 valueprobe_v(highp vec4 x) { return vec4(x.xyz, 2.0); } ";
constexpr std::string_view kOutput = "valueprobe_out";
// The probes' own names begin so, and a stage that names anything so is not probed: none of its
// names may shadow theirs. (Not `shadelab_`: shader/uniform_variants.h keeps that for its own.)
constexpr std::string_view kPrefix = "valueprobe_";

bool value_type(std::string_view type) { return one_of(type, {"float", "vec2", "vec3", "vec4"}); }
bool qualifier(std::string_view word) { return one_of(word, {"const", "highp", "mediump", "lowp"}); }

// Text put into the stage at a byte, or a byte span replaced.
struct Insertion {
  size_t begin, end;
  std::string text;
};

std::string probe_text(size_t k, std::string_view name) {
  return " if (" + std::string(kProbeUniform) + ".x == " + std::to_string(k) + ".0) " + std::string(kOutput) + " = valueprobe_v(" +
         std::string(name) + ");";
}

// The one `out vec4 NAME;` at the stage's top level: NAME's token, or size().
size_t output_name(const StageTokens& s) {
  size_t found = s.size();
  int depth = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    depth += s.is(i, "{") - s.is(i, "}");
    if (depth != 0 || !s.is(i, "out")) continue;
    size_t k = i + 1;
    if (qualifier(s.t[k].text)) ++k;
    if (!s.is(k, "vec4") || !s.identifier(k + 1) || !s.is(k + 2, ";") || found != s.size()) return s.size();
    found = k + 1;
  }
  return found;
}

// The `in`s the stage declares at its top level with a value type, each with its name.
std::vector<std::string_view> inputs_of(const StageTokens& s) {
  std::vector<std::string_view> out;
  for (size_t i = 0; i + 2 < s.size(); ++i) {
    if (!s.is(i, "in") || (i > 0 && !one_of(s.t[i - 1].text, {";", "}", "flat", "smooth", "es", ")"}))) continue;
    size_t k = i + 1;
    if (qualifier(s.t[k].text)) ++k;
    if (value_type(s.t[k].text) && s.identifier(k + 1) && s.is(k + 2, ";")) out.push_back(s.t[k + 1].text);
  }
  return out;
}

// The write a statement of main's that starts at `k` makes: the variable's token and the first
// token of its right-hand side; none for any other statement.
std::optional<std::pair<size_t, size_t>> write_at(const StageTokens& s, size_t k) {
  size_t j = k;
  while (j < s.size() && qualifier(s.t[j].text)) ++j;
  if (j + 2 < s.size() && value_type(s.t[j].text) && s.identifier(j + 1) && s.is(j + 2, "=")) return std::pair{j + 1, j + 3};
  if (!s.identifier(j) || one_of(s.t[j].text, {"if", "for", "while", "return", "else", "do", "discard"})) return std::nullopt;
  size_t m = j + 1;
  if (s.is(m, ".") && s.identifier(m + 1)) m += 2;
  if (one_of(s.t[std::min(m, s.size() - 1)].text, {"+", "-", "*", "/"}) && s.is(m + 1, "=")) return std::pair{j, m + 2};
  if (s.is(m, "=") && !s.is(m + 1, "=")) return std::pair{j, m + 1};
  return std::nullopt;
}

// main's locals (the output among them, once it is one) and the stage's inputs: a value a write
// reads that is not the page's (a uniform, a constant).
std::set<std::string, std::less<>> locals_of(const StageTokens& s, size_t open, std::string_view output) {
  std::set<std::string, std::less<>> out{std::string(output)};
  for (const auto input : inputs_of(s)) out.emplace(input);
  int depth = 0;
  for (size_t i = open; i + 1 < s.size(); ++i) {
    depth += s.is(i, "{") - s.is(i, "}");
    if (depth == 0) break;
    if (one_of(s.t[i].text, {"float", "vec2", "vec3", "vec4", "int", "bool", "mat3", "mat4"}) && s.identifier(i + 1) && !s.is(i + 2, "("))
      out.emplace(s.t[i + 1].text);
  }
  return out;
}

// The locals and inputs (`locals`) a write reads: its right-hand side's names, not calls nor
// fields; and its own variable where it is not declared here (`+=`, `x.y =`).
std::vector<std::string> locals_read(const StageTokens& s, size_t name, size_t rhs, size_t semicolon,
                                     const std::set<std::string, std::less<>>& locals) {
  std::vector<std::string> out;
  const auto add = [&](std::string_view n) {
    if (locals.count(n) && std::find(out.begin(), out.end(), n) == out.end()) out.emplace_back(n);
  };
  if (name > 0 && !value_type(s.t[name - 1].text) && !s.is(name + 1, "=")) add(s.t[name].text);
  for (size_t i = rhs; i < semicolon; ++i)
    if (s.identifier(i) && !s.is(i + 1, "(") && !s.is(i - 1, ".")) add(s.t[i].text);
  return out;
}

std::string with_insertions(std::string_view glsl, std::vector<Insertion> at) {
  std::stable_sort(at.begin(), at.end(), [](const Insertion& a, const Insertion& b) { return a.begin > b.begin; });
  std::string out(glsl);
  for (const auto& i : at) out.replace(i.begin, i.end - i.begin, i.text);
  return out;
}

// How each of `student`'s values reads beside the reference's: the same as its counterpart's,
// another, or without a counterpart to tell.
enum class ValueVerdict { same, differs, unknown };

// A verdict, and the reference probe it was read against (none where there is none).
struct Verdict {
  ValueVerdict verdict = ValueVerdict::unknown;
  std::optional<size_t> counterpart;
};

std::vector<Verdict> value_verdicts(const StageReading& stage, const ProbedStage& student, const ValueAgreement& agreement) {
  const auto reference = probed_fragment(stage.theirs.glsl);
  const size_t n = student.probes.size();
  if (!agreement.read || !reference || n == 0 || agreement.agrees_with.size() != n || agreement.differs_visibly.size() != n ||
      agreement.compared.size() != n)
    return {};
  std::vector<Verdict> out;
  for (size_t i = 0; i < student.probes.size(); ++i) {
    const ValueProbe& p = student.probes[i];
    // An input's counterpart is the reference's input of its name; a write's, the write of its
    // role at the same place in that variable's writes.
    const auto line = p.line >= 1 && static_cast<size_t>(p.line) <= stage.lines.size() ? stage.lines[static_cast<size_t>(p.line) - 1] : std::string_view();
    const std::string role = p.input ? p.name : stage.aligned.reference_name(p.name, line);
    std::optional<size_t> counterpart;
    for (size_t r = 0; r < reference->probes.size() && !role.empty(); ++r) {
      const ValueProbe& q = reference->probes[r];
      if (!q.end && q.input == p.input && q.name == role && (p.input || (q.ordinal == p.ordinal && q.last == p.last))) counterpart = r;
    }
    // The output's writes (the student's colour summed term by term, `fragColor += ...`, where the
    // reference sums into a local of its own): the last is what the stage outputs, the reference's
    // last value of its own output; one before it stands for a value only where the reference
    // computes that value too (ambient and diffuse summed, the reference's `color` before its
    // specular term), and is unknown otherwise.
    const bool output = !p.input && p.name == student.probes.back().name;
    if (output && !counterpart && p.last) counterpart = reference->probes.size() - 1;
    if (output && !counterpart && !p.end && agreement.compared[i] && !agreement.agrees_with[i].empty()) {
      out.push_back({ValueVerdict::same, std::nullopt});
      continue;
    }
    const auto holds = [&](const std::vector<int>& list) { return std::find(list.begin(), list.end(), static_cast<int>(*counterpart)) != list.end(); };
    if (p.end || !counterpart || !agreement.compared[i]) out.push_back({ValueVerdict::unknown, std::nullopt});
    else if (holds(agreement.agrees_with[i])) out.push_back({ValueVerdict::same, counterpart});
    else out.push_back({holds(agreement.differs_visibly[i]) ? ValueVerdict::differs : ValueVerdict::unknown, counterpart});
  }
  return out;
}

// Whether a value is, at every pixel both drew, one the reference writes other than its counterpart
// (`V` computed as `L`): no one change of the counterpart's says that, but the value is known.
bool holds_another_write(const ProbedStage& reference, const std::vector<int>& agrees_with, size_t counterpart) {
  return std::any_of(agrees_with.begin(), agrees_with.end(), [&](int r) {
    if (r < 0 || static_cast<size_t>(r) >= reference.probes.size() || static_cast<size_t>(r) == counterpart) return false;
    const ValueProbe& q = reference.probes[static_cast<size_t>(r)];
    return !q.input && !q.end;
  });
}

}  // namespace

std::optional<ProbedStage> probed_fragment(std::string_view glsl) {
  if (glsl.find("#version 300 es") == std::string_view::npos) return std::nullopt;
  const StageTokens s(glsl, shader::Stage::fragment);
  if (std::any_of(s.t.begin(), s.t.end(), [](const GlslToken& t) { return t.text.substr(0, kPrefix.size()) == kPrefix; })) return std::nullopt;
  const size_t open = main_start(s), output = output_name(s);
  if (open >= s.size() || output >= s.size() || open < 4) return std::nullopt;
  const TypedNames types = declared_types(s);
  const std::string_view out_name = s.t[output].text;
  const auto type_of = [&](std::string_view name) -> std::string_view {
    if (name == out_name) return "vec4";
    const auto it = types.find(name);
    return it == types.end() ? std::string_view() : std::string_view(it->second);
  };

  ProbedStage probed;
  std::vector<Insertion> insertions;
  // The student's output becomes a local of main's: a probe's value is what the stage outputs.
  insertions.push_back({s.begin(output), s.end(output), std::string(kOutput)});
  size_t main_name = open;  // `void main(void) {`: the return type is before `main`
  while (main_name > 0 && !s.is(main_name, "main")) --main_name;
  if (main_name == 0) return std::nullopt;
  insertions.push_back({s.begin(main_name - 1), s.begin(main_name - 1),
                        "uniform highp vec4 " + std::string(kProbeUniform) + "; " + std::string(kValueOf)});
  std::string at_start = " highp vec4 " + std::string(out_name) + " = vec4(0.0); " + std::string(kOutput) + " = vec4(0.0);";
  for (const auto input : inputs_of(s)) {
    at_start += probe_text(probed.probes.size(), input);
    probed.probes.push_back({true, false, std::string(input), s.t[open].line, 0, false, {}});
  }
  insertions.push_back({s.end(open), s.end(open), at_start});

  std::map<std::string, int, std::less<>> writes;  // each variable's writes so far
  const auto locals = locals_of(s, open, out_name);
  int depth = 0, parens = 0;
  for (size_t k = open; k < s.size(); ++k) {
    depth += s.is(k, "{") - s.is(k, "}");
    parens += s.is(k, "(") - s.is(k, ")");
    if (depth == 0) break;
    if (parens != 0 || k == open || !statement_start(s, k)) continue;
    const auto write = write_at(s, k);
    if (!write) continue;
    const auto [name, rhs] = *write;
    const size_t semicolon = statement_end(s, k);
    if (semicolon >= s.size() || rhs >= semicolon || type_of(s.t[name].text).empty()) continue;
    const std::string variable(s.t[name].text);
    insertions.push_back({s.end(semicolon), s.end(semicolon), probe_text(probed.probes.size(), variable)});
    probed.probes.push_back({false, false, variable, s.t[name].line, writes[variable]++, false, locals_read(s, name, rhs, semicolon, locals)});
  }
  if (probed.probes.empty()) return std::nullopt;
  size_t close = open;  // main's `}`
  for (int d = 0; close < s.size(); ++close)
    if ((d += s.is(close, "{") - s.is(close, "}")) == 0) break;
  if (close >= s.size()) return std::nullopt;
  insertions.push_back({s.begin(close), s.begin(close), probe_text(probed.probes.size(), out_name) + " "});
  probed.probes.push_back({false, true, std::string(out_name), s.t[close].line, 0, false, {}});
  for (auto p = probed.probes.rbegin(); p != probed.probes.rend(); ++p)
    if (!p->input && !p->end && std::none_of(probed.probes.rbegin(), p, [&](const ValueProbe& q) { return !q.input && !q.end && q.name == p->name; }))
      p->last = true;
  probed.glsl = with_insertions(glsl, std::move(insertions));
  return probed;
}

Departures departures(const ProgramReading& read, const ValueAgreement& agreement) {
  Departures out;
  if (!agreement.read) return out;
  const StageReading& stage = read[shader::Stage::fragment];
  const auto student = probed_fragment(stage.student.glsl);
  const auto reference = probed_fragment(stage.theirs.glsl);
  if (!student || !reference) return out;
  const auto verdicts = value_verdicts(stage, *student, agreement);
  if (verdicts.empty()) return out;
  std::map<std::string, ValueVerdict, std::less<>> holds;  // each local's and input's value as it stands
  for (size_t i = 0; i < student->probes.size(); ++i) {
    const ValueProbe& p = student->probes[i];
    const auto same = [&](const std::string& name) {
      const auto it = holds.find(name);
      return it != holds.end() && it->second == ValueVerdict::same;
    };
    const Verdict& v = verdicts[i];
    if (!p.input && v.verdict == ValueVerdict::differs && std::all_of(p.reads.begin(), p.reads.end(), same)) {
      auto& changes = out[p.line];
      if (i < agreement.changes.size())
        for (const auto& c : agreement.changes[i])
          if (static_cast<size_t>(c.reference) == *v.counterpart) changes.insert(c.change);
      if (changes.empty() && holds_another_write(*reference, agreement.agrees_with[i], *v.counterpart)) changes.insert(ValueChange::replaced);
    }
    holds[p.name] = v.verdict;
  }
  return out;
}

std::set<int> lines_of(const Departures& d) {
  std::set<int> out;
  for (const auto& [line, changes] : d) out.insert(line);
  return out;
}

bool makes_departing_change(const RepairEdit& e, const Departures& at) {
  const auto it = at.find(e.line);
  if (e.stage != shader::Stage::fragment || it == at.end()) return false;
  return std::any_of(it->second.begin(), it->second.end(), [&](ValueChange c) { return makes(e.kind, c); });
}

// Both stages' probes, and the student's probe of the write `edit` changes (the last write of its
// subject on its line), where the values were read and compared it.
struct EditedWrite {
  ProbedStage student, reference;
  size_t write = 0;
};
std::optional<EditedWrite> edited_write(const StageReading& stage, const RepairEdit& edit, const ValueAgreement& agreement) {
  if (!agreement.read || edit.stage != shader::Stage::fragment) return std::nullopt;
  auto student = probed_fragment(stage.student.glsl);
  auto reference = probed_fragment(stage.theirs.glsl);
  if (!student || !reference || agreement.agrees_with.size() != student->probes.size() ||
      agreement.compared.size() != student->probes.size())
    return std::nullopt;
  std::optional<size_t> write;
  for (size_t i = 0; i < student->probes.size(); ++i) {
    const ValueProbe& p = student->probes[i];
    if (!p.input && !p.end && p.name == edit.subject && p.line == edit.line) write = i;
  }
  if (!write || !agreement.compared[*write]) return std::nullopt;
  return EditedWrite{std::move(*student), std::move(*reference), *write};
}

std::vector<std::string> values_it_holds(const ProgramReading& read, const RepairEdit& edit, const ValueAgreement& agreement) {
  std::vector<std::string> out;
  const StageReading& stage = read[shader::Stage::fragment];
  const auto found = edited_write(stage, edit, agreement);
  if (!found) return out;
  const auto& [student, reference, write] = *found;
  const std::string role = stage.aligned.reference_name(edit.subject, stage.line_of(edit));
  for (const int r : agreement.agrees_with[write]) {
    if (r < 0 || static_cast<size_t>(r) >= reference.probes.size()) continue;
    const ValueProbe& q = reference.probes[static_cast<size_t>(r)];
    if (!q.input && !q.end && q.name != role && std::find(out.begin(), out.end(), q.name) == out.end()) out.push_back(q.name);
  }
  return out;
}

bool value_stands_for(const ProgramReading& read, const RepairEdit& edit, const ValueAgreement& agreement, std::string_view role) {
  const auto found = edited_write(read[shader::Stage::fragment], edit, agreement);
  if (!found) return false;
  const auto& [student, reference, write] = *found;
  const auto is_role = [&](int r) {
    if (r < 0 || static_cast<size_t>(r) >= reference.probes.size()) return false;
    const ValueProbe& q = reference.probes[static_cast<size_t>(r)];
    return !q.input && !q.end && q.name == role;
  };
  const auto& agrees = agreement.agrees_with[write];
  if (std::any_of(agrees.begin(), agrees.end(), is_role)) return true;
  if (write >= agreement.changes.size()) return false;
  const auto& changes = agreement.changes[write];
  return std::any_of(changes.begin(), changes.end(), [&](const ValueChangeTo& c) { return is_role(c.reference); });
}

}  // namespace shadelab::repair
