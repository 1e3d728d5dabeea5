#include "repair/stage_names.h"

namespace shadelab::repair {

TypedNames declared_types(const StageTokens& s) {
  TypedNames types;
  for (size_t i = 0; i + 1 < s.size(); ++i)
    if (one_of(s.t[i].text, {"float", "vec2", "vec3", "vec4", "mat3", "mat4"}) && s.identifier(i + 1) && !s.is(i + 2, "("))
      types.emplace(std::string(s.t[i + 1].text), std::string(s.t[i].text));
  return types;
}

TypedNames read_only_names(const StageTokens& s) {
  TypedNames names;
  for (size_t i = 0; i + 2 < s.size(); ++i) {
    if (!one_of(s.t[i].text, {"uniform", "in", "attribute", "varying"})) continue;
    if (s.stage == shader::Stage::vertex && s.is(i, "varying")) continue;  // a vertex stage writes its varyings
    size_t k = i + 1;
    if (one_of(s.t[k].text, {"lowp", "mediump", "highp", "flat", "smooth"})) ++k;
    if (s.identifier(k) && s.identifier(k + 1) && s.is(k + 2, ";")) names.emplace(std::string(s.t[k + 1].text), std::string(s.t[k].text));
  }
  return names;
}

bool read_at(const StageTokens& s, size_t i) {
  if (i > 0 && (s.is(i - 1, ".") || (s.identifier(i - 1) && !s.is(i - 1, "return")))) return false;  // a field, or a declaration
  return !(s.is(i + 1, "=") && !s.is(i + 2, "="));
}

size_t main_start(const StageTokens& s) {
  for (size_t i = 0; i + 1 < s.size(); ++i)
    if (s.is(i, "main") && s.is(i + 1, "(") && s.is(s.close_of(i + 1) + 1, "{")) return s.close_of(i + 1) + 1;
  return s.size();
}

std::vector<std::pair<size_t, size_t>> conditions_of(const StageTokens& s) {
  std::vector<std::pair<size_t, size_t>> out;
  for (size_t i = 0; i + 2 < s.size(); ++i) {
    if (!s.is(i, "if") || !s.is(i + 1, "(")) continue;
    const size_t close = s.close_of(i + 1);
    if (close < s.size() && close > i + 2) out.push_back({i + 2, close - 1});
  }
  return out;
}

bool statement_start(const StageTokens& s, size_t i) { return i > 0 && one_of(s.t[i - 1].text, {";", "{", "}"}); }

size_t statement_end(const StageTokens& s, size_t i) {
  while (i < s.size() && !s.is(i, ";")) ++i;
  return i;
}

bool has_token(const StageTokens& s, std::string_view text, size_t first, size_t last) {
  for (size_t k = first; k <= last && k < s.size(); ++k)
    if (s.is(k, text)) return true;
  return false;
}

size_t calls_of(const StageTokens& s, std::string_view name) {
  size_t n = 0;
  for (size_t i = 0; i + 1 < s.size(); ++i) n += s.is(i, name) && s.is(i + 1, "(");
  return n;
}

bool reads(const StageTokens& s, std::string_view name) {
  for (size_t i = 0; i < s.size(); ++i)
    if (s.is(i, name) && read_at(s, i)) return true;
  return false;
}

bool main_of(const StageTokens& s, size_t i) {
  const size_t open = main_start(s);
  if (open >= s.size() || i <= open) return false;
  int depth = 0;
  for (size_t k = open; k < i; ++k) depth += s.is(k, "{") - s.is(k, "}");
  return depth > 0;
}

std::vector<Helper> helpers_of(const StageTokens& s) {
  std::vector<Helper> out;
  for (size_t i = 0; i + 3 < s.size(); ++i) {
    if (!one_of(s.t[i].text, {"float", "vec2", "vec3", "vec4"}) || !s.identifier(i + 1) || !s.is(i + 2, "(")) continue;
    if (i > 0 && !one_of(s.t[i - 1].text, {";", "}"})) continue;  // a call or a constructor, not a definition
    const size_t close_params = s.close_of(i + 2);
    if (!s.is(close_params + 1, "{")) continue;
    size_t depth = 0, end = close_params + 1;
    for (; end < s.size(); ++end) {
      depth += s.is(end, "{");
      if (s.is(end, "}") && --depth == 0) break;
    }
    if (end < s.size()) out.push_back({s.t[i].text, i + 3, close_params - 1, close_params + 1, end});
  }
  return out;
}

}  // namespace shadelab::repair
