#include "course/script_facts.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <functional>
#include <numbers>

namespace shadelab::course {

namespace {

// Names bound to names: enough for any course's script, and never a cycle's recursion.
constexpr int kMaxDepth = 8;

bool identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '$'; }

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// The script without its comments; a string is copied whole, so "http://" stays.
std::string without_comments(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size();) {
    const char c = s[i];
    if (c == '"' || c == '\'' || c == '`') {
      const size_t start = i++;
      while (i < s.size() && s[i] != c) i += s[i] == '\\' ? 2 : 1;
      i = std::min(i + 1, s.size());
      out.append(s.substr(start, i - start));
    } else if (s.substr(i, 2) == "//") {
      i = std::min(s.find('\n', i), s.size());
    } else if (s.substr(i, 2) == "/*") {
      const size_t end = s.find("*/", i + 2);
      i = end == std::string_view::npos ? s.size() : end + 2;
      out += ' ';
    } else {
      out += s[i++];
    }
  }
  return out;
}

// The script with each string's contents blanked (its length kept): code, where a call or a
// declaration may be, without a string's text that looks like one.
std::string without_strings(std::string_view s) {
  std::string out(s);
  for (size_t i = 0; i < out.size(); ++i) {
    const char quote = out[i];
    if (quote != '"' && quote != '\'' && quote != '`') continue;
    for (++i; i < out.size() && out[i] != quote; ++i) {
      if (out[i] == '\\' && i + 1 < out.size()) out[i++] = ' ';
      out[i] = ' ';
    }
  }
  return out;
}

// The position of the bracket closing the one that opens at `open`, or npos.
size_t closing(std::string_view s, size_t open) {
  int depth = 0;
  for (size_t i = open; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '"' || c == '\'' || c == '`') {
      for (++i; i < s.size() && s[i] != c; i += s[i] == '\\' ? 2 : 1) {
      }
    } else if (c == '(' || c == '[' || c == '{') {
      ++depth;
    } else if (c == ')' || c == ']' || c == '}') {
      if (--depth == 0) return i;
    }
  }
  return std::string_view::npos;
}

// `inside` split at its top-level commas, each part trimmed.
std::vector<std::string> split_arguments(std::string_view inside) {
  std::vector<std::string> out;
  size_t start = 0;
  int depth = 0;
  for (size_t i = 0; i <= inside.size(); ++i) {
    const char c = i < inside.size() ? inside[i] : ',';
    depth += (c == '(' || c == '[' || c == '{') ? 1 : (c == ')' || c == ']' || c == '}') ? -1 : 0;
    if (c == ',' && depth == 0) {
      out.emplace_back(trimmed(inside.substr(start, i - start)));
      start = i + 1;
    }
  }
  if (out.size() == 1 && out[0].empty()) out.clear();
  return out;
}

// Recursive descent over + - * / ( ), numbers and names; a name is the caller's to resolve.
class Arithmetic {
 public:
  using Resolve = std::function<std::optional<double>(std::string_view)>;
  Arithmetic(std::string_view s, Resolve resolve) : s_(s), resolve_(std::move(resolve)) {}

  std::optional<double> whole() {
    auto v = sum();
    skip();
    if (at_ != s_.size()) return std::nullopt;
    return v;
  }

 private:
  void skip() {
    while (at_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[at_]))) ++at_;
  }
  bool eat(char c) {
    skip();
    if (at_ < s_.size() && s_[at_] == c) return ++at_, true;
    return false;
  }

  // The operator at the cursor when it is one of `ops` (taken), else 0.
  char take_operator(std::string_view ops) {
    skip();
    if (at_ < s_.size() && ops.find(s_[at_]) != std::string_view::npos) return s_[at_++];
    return 0;
  }

  // One level of left-associative operators, `operand (op operand)*`; `apply` has no value where
  // the operation has none (a division by 0), and nothing after it has one either.
  template <class Apply>
  std::optional<double> chain(std::optional<double> (Arithmetic::*operand)(), std::string_view ops, Apply apply) {
    auto v = (this->*operand)();
    while (v) {
      const char op = take_operator(ops);
      if (op == 0) break;
      const auto r = (this->*operand)();
      v = r ? apply(op, *v, *r) : std::nullopt;
    }
    return v;
  }

  std::optional<double> sum() {
    return chain(&Arithmetic::product, "+-", [](char op, double a, double b) { return std::optional(op == '+' ? a + b : a - b); });
  }

  std::optional<double> product() {
    return chain(&Arithmetic::unary, "*/", [](char op, double a, double b) -> std::optional<double> {
      if (op == '*') return a * b;
      return b != 0 ? std::optional(a / b) : std::nullopt;
    });
  }

  std::optional<double> unary() {
    if (eat('-')) {
      const auto v = unary();
      return v ? std::optional(-*v) : std::nullopt;
    }
    if (eat('+')) return unary();
    return primary();
  }

  std::optional<double> primary() {
    skip();
    if (eat('(')) {
      const auto v = sum();
      return eat(')') ? v : std::nullopt;
    }
    if (at_ == s_.size()) return std::nullopt;
    const char c = s_[at_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      double v = 0;
      const auto [end, ec] = std::from_chars(s_.data() + at_, s_.data() + s_.size(), v);
      if (ec != std::errc()) return std::nullopt;
      at_ = static_cast<size_t>(end - s_.data());
      return v;
    }
    if (!identifier_char(c) || std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
    const size_t start = at_;
    while (at_ < s_.size() && (identifier_char(s_[at_]) || s_[at_] == '.')) ++at_;
    const std::string_view name = s_.substr(start, at_ - start);
    if (name == "Math.PI") return std::numbers::pi;
    if (eat('(')) {  // only the degree helpers: anything else is not stated here
      const std::string_view last = name.substr(name.rfind('.') == std::string_view::npos ? 0 : name.rfind('.') + 1);
      if (last != "toRadian" && last != "degToRad" && last != "toRadians") return std::nullopt;
      const auto degrees = sum();
      return degrees && eat(')') ? std::optional(*degrees * std::numbers::pi / 180) : std::nullopt;
    }
    return resolve_(name);
  }

  std::string_view s_;
  size_t at_ = 0;
  Resolve resolve_;
};

// The declarations `const|let|var a = x, b = y` of a script, each name with the text bound to it:
// to the first `;` or the first line end outside brackets (a statement without its `;`).
std::vector<std::pair<std::string, std::string>> declarations(const std::string& text) {
  static const std::regex keyword(R"(\b(?:const|let|var)\s+)");
  static const std::regex binding(R"(^([A-Za-z_$][\w$]*)\s*=([^=>][\s\S]*)$)");
  std::vector<std::pair<std::string, std::string>> out;
  for (std::sregex_iterator it(text.begin(), text.end(), keyword), end; it != end; ++it) {
    const size_t start = static_cast<size_t>(it->position() + it->length());
    size_t stop = start;
    while (stop < text.size() && text[stop] != ';' && text[stop] != '\n') {
      const char c = text[stop];
      if (c == '(' || c == '[' || c == '{' || c == '"' || c == '\'' || c == '`') {
        const size_t close = c == '(' || c == '[' || c == '{' ? closing(text, stop) : text.find(c, stop + 1);
        stop = close == std::string::npos ? text.size() : close + 1;
      } else {
        ++stop;
      }
    }
    for (const auto& part : split_arguments(std::string_view(text).substr(start, stop - start))) {
      std::smatch m;
      if (std::regex_match(part, m, binding)) out.emplace_back(m[1].str(), std::string(trimmed(m[2].str())));
    }
  }
  return out;
}

}  // namespace

ScriptFacts::ScriptFacts(std::string_view script) : text_(without_comments(script)), code_(without_strings(text_)) {
  for (auto& [name, bound] : declarations(code_)) bound_.emplace(std::move(name), std::move(bound));  // the first: a `let` may change later
}

std::optional<double> ScriptFacts::number(std::string_view expression) const { return number(expression, 0); }

std::optional<double> ScriptFacts::number(std::string_view expression, int depth) const {
  if (depth > kMaxDepth) return std::nullopt;
  return Arithmetic(expression, [this, depth](std::string_view name) -> std::optional<double> {
           const auto b = bound_.find(name);
           return b == bound_.end() ? std::nullopt : number(b->second, depth + 1);
         }).whole();
}

std::optional<std::vector<double>> ScriptFacts::numbers(std::string_view expression) const { return numbers(expression, 0); }

std::optional<std::vector<double>> ScriptFacts::numbers(std::string_view expression, int depth) const {
  if (depth > kMaxDepth) return std::nullopt;
  std::string_view e = trimmed(expression);
  for (const std::string_view wrapper : {"new Float32Array(", "Float32Array.from(", "new Float64Array("})
    if (e.starts_with(wrapper) && e.ends_with(")")) e = trimmed(e.substr(wrapper.size(), e.size() - wrapper.size() - 1));
  if (e.starts_with("[") && closing(e, 0) == e.size() - 1) {
    std::vector<double> out;
    for (const auto& item : split_arguments(e.substr(1, e.size() - 2))) {
      const auto v = number(item, depth);
      if (!v) return std::nullopt;
      out.push_back(*v);
    }
    return out;
  }
  const auto b = bound_.find(e);
  return b == bound_.end() ? std::nullopt : numbers(b->second, depth + 1);
}

std::vector<std::vector<std::string>> ScriptFacts::calls(const std::regex& callee) const {
  static const std::regex named_call(R"(([A-Za-z_$][\w$]*(?:\.[A-Za-z_$][\w$]*)*)\s*\()");
  static const std::regex definition(R"(\bfunction\s*$)");
  std::vector<std::vector<std::string>> out;
  for (std::sregex_iterator it(code_.begin(), code_.end(), named_call), end; it != end; ++it) {
    const auto at = static_cast<size_t>(it->position());
    if (at > 0 && (identifier_char(code_[at - 1]) || code_[at - 1] == '.')) continue;  // the tail of a longer name
    if (!std::regex_match((*it)[1].str(), callee)) continue;
    if (std::regex_search(code_.substr(at >= 16 ? at - 16 : 0, at >= 16 ? 16 : at), definition)) continue;
    const size_t open = at + static_cast<size_t>(it->length()) - 1;
    const size_t close = closing(code_, open);
    if (close == std::string::npos) continue;
    out.push_back(split_arguments(std::string_view(text_).substr(open + 1, close - open - 1)));
  }
  return out;
}

std::optional<double> ScriptFacts::factor_of(std::string_view name, std::string_view within) const {
  const std::string word(name), operand = R"(([A-Za-z_$][\w$.]*|[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?))";
  const std::regex before(operand + R"(\s*\*\s*)" + word + R"(\b)"), after(R"(\b)" + word + R"(\s*\*\s*)" + operand);
  const std::string text(within);
  for (const auto* form : {&before, &after}) {
    for (std::sregex_iterator it(text.begin(), text.end(), *form), end; it != end; ++it) {
      const std::string k = (*it)[1].str();
      if (k == word) continue;
      if (const auto v = number(k)) return v;
    }
  }
  return std::nullopt;
}

std::optional<double> ScriptFacts::factor_of(std::string_view name) const { return factor_of(name, code_); }

namespace {

// -0.0 (the course writes [-0.0, -2.0, -7.5]) is 0 in a profile.
double without_negative_zero(double v) { return v + 0.0; }

}  // namespace

std::optional<PageProjection> projection_of(const ScriptFacts& script) {
  static const std::regex perspective(R"((?:[\w$]+\.)?(?:mat4)?[Pp]erspective)");
  for (const auto& arguments : script.calls(perspective)) {
    std::vector<double> known;
    for (const auto& a : arguments)
      if (const auto v = script.number(a)) known.push_back(*v);
    if (known.size() < 3) continue;
    const double fov = known.front() < std::numbers::pi ? known.front() * 180 / std::numbers::pi : known.front();
    return PageProjection{std::round(fov * 1e9) / 1e9, known[known.size() - 2], known.back()};
  }
  return std::nullopt;
}

std::optional<std::array<double, 3>> mesh_translation_of(const ScriptFacts& script) {
  static const std::regex translate(R"((?:[\w$]+\.)?(?:mat4)?[Tt]ranslate?)");
  for (const auto& arguments : script.calls(translate))
    for (const auto& a : arguments)
      if (const auto v = script.numbers(a); v && v->size() == 3)
        return std::array{without_negative_zero((*v)[0]), without_negative_zero((*v)[1]), without_negative_zero((*v)[2])};
  return std::nullopt;
}

std::optional<double> degrees_per_second_of(const ScriptFacts& script) {
  static const std::regex rotation(R"((?:[\w$]+\.)?\w*[Rr]otat\w*)");
  for (const auto& arguments : script.calls(rotation))
    for (const auto& a : arguments)
      if (const auto k = script.factor_of("TIME", a)) return k;
  return script.factor_of("TIME");
}

}  // namespace shadelab::course
