#include "shader/condition_value.h"

#include <array>
#include <cctype>
#include <stdexcept>
#include <string>
#include <vector>

#include "shader/glsl_lines.h"

namespace shadelab::shader {

namespace {

// Binary operators from the loosest binding to the tightest (C's table, as GLSL ES 3.00 section
// 3.4 takes it; no `?:`, no `,`).
constexpr std::array<std::array<std::string_view, 4>, 10> kLevels{{
    {"||"}, {"&&"}, {"|"}, {"^"}, {"&"}, {"==", "!="}, {"<", ">", "<=", ">="}, {"<<", ">>"}, {"+", "-"}, {"*", "/", "%"},
}};

class Reader {
 public:
  explicit Reader(std::vector<std::string> tokens) : tokens_(std::move(tokens)) {}

  std::optional<long long> whole() {
    const auto value = binary(0, true);
    return value && at_ == tokens_.size() ? value : std::nullopt;
  }

 private:
  // `live`: the value counts; a side `&&` or `||` skips is read, and may divide by zero.
  std::optional<long long> binary(size_t level, bool live) {
    if (level == kLevels.size()) return unary(live);
    auto left = binary(level + 1, live);
    while (left && at_ < tokens_.size()) {
      const std::string op = tokens_[at_];
      bool found = false;
      for (const auto& candidate : kLevels[level]) found = found || (!candidate.empty() && candidate == op);
      if (!found) break;
      ++at_;
      const bool right_live = live && !((op == "&&" && *left == 0) || (op == "||" && *left != 0));
      const auto right = binary(level + 1, right_live);
      if (!right) return std::nullopt;
      left = apply(op, *left, *right, right_live);
    }
    return left;
  }

  static std::optional<long long> apply(const std::string& op, long long a, long long b, bool live) {
    if (op == "||") return a != 0 || b != 0;
    if (op == "&&") return a != 0 && b != 0;
    if (op == "|") return a | b;
    if (op == "^") return a ^ b;
    if (op == "&") return a & b;
    if (op == "==") return a == b;
    if (op == "!=") return a != b;
    if (op == "<") return a < b;
    if (op == ">") return a > b;
    if (op == "<=") return a <= b;
    if (op == ">=") return a >= b;
    if (op == "<<" || op == ">>") return b < 0 || b > 31 ? std::nullopt : std::optional(op == "<<" ? a << b : a >> b);
    if (op == "+") return a + b;
    if (op == "-") return a - b;
    if (op == "*") return a * b;
    if (b == 0) return live ? std::nullopt : std::optional(0LL);  // skipped: its value never counts
    return op == "/" ? a / b : a % b;
  }

  // Parentheses and unary operators nest at most this deep here; deeper stays glslang's (a
  // hostile line must not run the worker out of stack).
  static constexpr int kMaxNesting = 64;

  std::optional<long long> unary(bool live) {
    if (at_ >= tokens_.size() || depth_ >= kMaxNesting) return std::nullopt;
    ++depth_;
    const auto value = unary_inside(live);
    --depth_;
    return value;
  }

  std::optional<long long> unary_inside(bool live) {
    const std::string t = tokens_[at_++];
    if (t == "(") {
      const auto value = binary(0, live);
      if (!value || at_ >= tokens_.size() || tokens_[at_++] != ")") return std::nullopt;
      return value;
    }
    if (t == "+" || t == "-" || t == "~" || t == "!") {
      const auto value = unary(live);
      if (!value) return std::nullopt;
      return t == "+" ? *value : t == "-" ? -*value : t == "~" ? ~*value : static_cast<long long>(*value == 0);
    }
    return number(t);
  }

  static std::optional<long long> number(const std::string& t) {
    if (t.empty() || !std::isdigit(static_cast<unsigned char>(t[0]))) return std::nullopt;
    size_t used = 0;
    try {
      const long long value = std::stoll(t, &used, 0);  // decimal, 0-octal, 0x-hex, as C reads them
      if (used == t.size() && value <= 0x7fffffff) return value;
    } catch (const std::exception&) {
    }
    return std::nullopt;
  }

  std::vector<std::string> tokens_;
  size_t at_ = 0;
  int depth_ = 0;
};

// Two-character operators joined from the tokenizer's single characters.
std::optional<std::vector<std::string>> operator_tokens(std::string_view condition) {
  const std::vector<GlslToken> raw = tokens_of(condition);
  std::vector<std::string> out;
  for (size_t i = 0; i < raw.size(); ++i) {
    if (raw[i].kind == GlslToken::Kind::identifier) return std::nullopt;
    std::string t(raw[i].text);
    if (raw[i].kind == GlslToken::Kind::punctuation && i + 1 < raw.size() && raw[i + 1].column == raw[i].column + 1 &&
        raw[i + 1].line == raw[i].line) {
      const std::string two = t + std::string(raw[i + 1].text);
      for (const std::string_view op : {"||", "&&", "==", "!=", "<=", ">=", "<<", ">>"})
        if (two == op) {
          t = two;
          ++i;
          break;
        }
    }
    out.push_back(std::move(t));
  }
  return out;
}

}  // namespace

std::optional<long long> literal_condition_value(std::string_view condition) {
  auto tokens = operator_tokens(condition);
  if (!tokens || tokens->empty()) return std::nullopt;
  return Reader(std::move(*tokens)).whole();
}

}  // namespace shadelab::shader
