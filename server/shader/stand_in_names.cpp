#include "shader/stand_in_names.h"

#include "shader/glsl_lines.h"

namespace shadelab::shader {

namespace {

bool uses_word(std::string_view text, std::string_view word) { return whole_word(text, word) != std::string_view::npos; }

void replace_words(std::string& text, std::string_view word, std::string_view with) {
  size_t from = 0;
  for (;;) {
    const size_t at = whole_word(std::string_view(text).substr(from), word);
    if (at == std::string_view::npos) return;
    text.replace(from + at, word.size(), with);
    from += at + with.size();
  }
}

// "q" and digits, as long as the word, the first that neither source uses ("q0000", "q0001", ...).
std::string stand_in_for(std::string_view word, const std::string& vertex, const std::string& fragment) {
  for (int n = 0;; ++n) {
    std::string digits = std::to_string(n);
    if (digits.size() + 1 > word.size()) return {};  // every stand-in taken: the word stays
    const std::string name = "q" + std::string(word.size() - 1 - digits.size(), '0') + digits;
    if (!uses_word(vertex, name) && !uses_word(fragment, name)) return name;
  }
}

}  // namespace

std::vector<StandIn> rename_reserved_names(std::string& vertex, std::string& fragment, NamesFor use) {
  const std::vector<std::string_view> words =
      use == NamesFor::front_end ? std::vector<std::string_view>{"dmat2"} : std::vector<std::string_view>{"packed"};
  std::vector<StandIn> renamed;
  for (const auto word : words) {
    if (!uses_word(vertex, word) && !uses_word(fragment, word)) continue;
    std::string stand_in = stand_in_for(word, vertex, fragment);
    if (stand_in.empty()) continue;
    replace_words(vertex, word, stand_in);
    replace_words(fragment, word, stand_in);
    renamed.push_back({std::string(word), std::move(stand_in)});
  }
  return renamed;
}

void restore_names(std::string& text, const std::vector<StandIn>& renamed) {
  for (const auto& r : renamed) replace_words(text, r.stand_in, r.word);
}

void restore_names(std::vector<Diagnostic>& diagnostics, const std::vector<StandIn>& renamed) {
  for (auto& d : diagnostics) restore_names(d.message, renamed);
}

}  // namespace shadelab::shader
