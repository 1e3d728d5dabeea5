#include "repair/live_statements.h"

#include <algorithm>
#include <optional>

#include "shader/glsl_lines.h"

namespace shadelab::repair {

namespace {

using shader::GlslToken;

bool touching(const GlslToken& a, const GlslToken& b) { return a.text.data() + a.text.size() == b.text.data(); }

// Where the assignment whose `=` is token `k` starts (`+=` is two tokens, `+` and `=`); none for
// a `=` of `==`, `<=`, `>=` or `!=`.
std::optional<size_t> assignment_at(const std::vector<GlslToken>& t, size_t k) {
  if (t[k].text != "=") return std::nullopt;
  if (k + 1 < t.size() && t[k + 1].text == "=" && touching(t[k], t[k + 1])) return std::nullopt;
  if (k == 0 || !touching(t[k - 1], t[k])) return k;
  const std::string_view before = t[k - 1].text;
  if (before == "=" || before == "<" || before == ">" || before == "!") return std::nullopt;
  if (before == "+" || before == "-" || before == "*" || before == "/") return k - 1;
  return k;
}

// A run of tokens between `;`, `{` and `}`: the name it assigns, or whether it reads names
// whatever it writes (a condition, a loop, a return, a call); a declaration alone reads none.
struct Statement {
  size_t first = 0, last = 0;  // tokens, inclusive
  std::string_view target;
  bool reads_always = false;
  // An if, for or while with a block: it reads its names only where its block (with the else
  // blocks after it) holds a live statement. The block's last token.
  std::optional<size_t> guards_to;
};

// The token that closes the block opened at `open` (a `{`).
size_t block_end(const std::vector<GlslToken>& t, size_t open) {
  int depth = 0;
  for (size_t i = open; i < t.size(); ++i) {
    if (t[i].text == "{") ++depth;
    if (t[i].text == "}" && --depth == 0) return i;
  }
  return t.size() - 1;
}

// The end of the block opened at `open` and of every `else` block chained after it.
size_t guarded_end(const std::vector<GlslToken>& t, size_t open) {
  size_t end = block_end(t, open);
  while (end + 1 < t.size() && t[end + 1].text == "else") {
    size_t next = end + 2;
    while (next < t.size() && t[next].text != "{" && t[next].text != ";") ++next;
    if (next >= t.size() || t[next].text != "{") return next < t.size() ? next : t.size() - 1;
    end = block_end(t, next);
  }
  return end;
}

// The name an assignment at token `op` writes: the identifier before it, past fields and indices.
std::string_view target_before(const std::vector<GlslToken>& t, size_t first, size_t op) {
  size_t i = op;
  while (i > first) {
    --i;
    if (t[i].text == "]") {
      int depth = 0;
      for (; i > first; --i) {
        if (t[i].text == "]") ++depth;
        if (t[i].text == "[" && --depth == 0) break;
      }
      continue;
    }
    if (t[i].kind != GlslToken::Kind::identifier) return {};
    if (i > first && t[i - 1].text == ".") {
      --i;
      continue;
    }
    return t[i].text;
  }
  return {};
}

std::vector<Statement> statements(const std::vector<GlslToken>& t) {
  std::vector<Statement> out;
  size_t first = 0;
  int paren = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    const std::string_view s = t[i].text;
    if (s == "(") ++paren;
    if (s == ")") --paren;
    const bool boundary = (s == ";" && paren == 0) || s == "{" || s == "}";
    if (!boundary) continue;
    if (i > first) {
      Statement st{first, i - 1, {}};
      const bool control = t[first].text == "if" || t[first].text == "for" || t[first].text == "while" || t[first].text == "return";
      int depth = 0;
      for (size_t k = first; k < i && !control; ++k) {
        if (t[k].text == "(" || t[k].text == "[") ++depth;
        if (t[k].text == ")" || t[k].text == "]") --depth;
        if (depth != 0) continue;
        if (auto op = assignment_at(t, k)) {
          st.target = target_before(t, first, *op);
          break;
        }
      }
      if (control && s == "{" && t[first].text != "return") st.guards_to = guarded_end(t, i);
      if (st.target.empty())
        st.reads_always = control || std::any_of(t.begin() + first, t.begin() + i, [](const GlslToken& x) {
                            return x.text == "(" || x.text == "+" || x.text == "-";  // a call, or x++ / x--
                          });
      out.push_back(st);
    }
    first = i + 1;
  }
  return out;
}

// The names declared with one of `qualifiers` (out, varying...) in `t`.
std::set<std::string, std::less<>> declared_as(const std::vector<GlslToken>& t, std::initializer_list<std::string_view> qualifiers) {
  std::set<std::string, std::less<>> names;
  for (size_t i = 0; i + 2 < t.size(); ++i) {
    if (std::find(qualifiers.begin(), qualifiers.end(), t[i].text) == qualifiers.end()) continue;
    size_t k = i + 1;
    while (k + 1 < t.size() && t[k + 1].kind == GlslToken::Kind::identifier) ++k;  // precision, type
    if (k > i + 1 && t[k].kind == GlslToken::Kind::identifier) names.emplace(t[k].text);
  }
  return names;
}

StageLiveness liveness(const StageTokens& stage, std::set<std::string, std::less<>> outputs) {
  const std::vector<GlslToken>& t = stage.t;
  const auto all = statements(t);
  StageLiveness out{std::move(outputs), {}};
  const auto read_names = [&](const Statement& s) {
    bool added = false;
    for (size_t k = s.first; k <= s.last; ++k)
      if (t[k].kind == GlslToken::Kind::identifier) added |= out.live_names.emplace(t[k].text).second;
    return added;
  };
  std::vector<bool> live(all.size(), false);
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t i = 0; i < all.size(); ++i) {
      const Statement& s = all[i];
      bool now = !s.target.empty() ? out.live_names.count(s.target) > 0 : s.reads_always && !s.guards_to;
      for (size_t k = i + 1; s.guards_to && !now && k < all.size() && all[k].last < *s.guards_to; ++k) now = live[k];
      if (!now) continue;
      changed |= !live[i];
      live[i] = true;
      changed |= read_names(s);
    }
  }
  const auto byte = [&](const GlslToken& token) { return static_cast<size_t>(token.text.data() - stage.glsl.data()); };
  // Dead: an assignment to a name nothing live reads, and a condition whose blocks hold nothing live.
  for (size_t i = 0; i < all.size(); ++i) {
    const Statement& s = all[i];
    if ((!s.target.empty() && !out.live_names.count(s.target)) || (s.guards_to && !live[i]))
      out.dead_spans.emplace_back(byte(t[s.first]), byte(t[s.last]) + t[s.last].text.size());
  }
  return out;
}

}  // namespace

bool StageLiveness::dead(size_t byte) const {
  return std::any_of(dead_spans.begin(), dead_spans.end(), [&](const auto& s) { return byte >= s.first && byte < s.second; });
}

StageLiveness fragment_liveness(const StageTokens& fragment) {
  auto outputs = declared_as(fragment.t, {"out"});
  outputs.insert({"gl_FragColor", "gl_FragData"});
  return liveness(fragment, std::move(outputs));
}

StageLiveness vertex_liveness(const StageTokens& vertex, const std::set<std::string, std::less<>>& fragment_reads) {
  std::set<std::string, std::less<>> outputs{"gl_Position", "gl_PointSize"};
  for (const auto& name : declared_as(vertex.t, {"out", "varying"}))
    if (fragment_reads.count(name)) outputs.insert(name);
  return liveness(vertex, std::move(outputs));
}

}  // namespace shadelab::repair
