#include "shader/global_scan.h"

#include <algorithm>
#include <cctype>

namespace shadelab::shader {

namespace {

bool starts_identifier(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool continues_identifier(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

class Scanner {
 public:
  explicit Scanner(std::string_view glsl) : glsl_(glsl) {}

  GlslScan run() {
    for (size_t i = 0; i < glsl_.size();) i = step(i);
    return std::move(scan_);
  }

 private:
  size_t step(size_t i) {
    const char c = glsl_[i];
    if (glsl_.substr(i, 2) == "//") return skip_to(i, "\n");
    if (glsl_.substr(i, 2) == "/*") return skip_to(i, "*/") + 2;
    if (c == '#' && at_line_start(i)) {
      directive(i + 1);
      return skip_to(i, "\n");
    }
    if (starts_identifier(c)) return identifier(i);
    if (c == '{' || c == '}') {
      depth_ += c == '{' ? 1 : -1;
      restart();
    } else if (depth_ == 0) {
      punctuation(c, i);
    }
    return i + 1;
  }

  // The directive's name after the '#' at `i` - 1 (spaces allowed between).
  void directive(size_t i) {
    while (i < glsl_.size() && (glsl_[i] == ' ' || glsl_[i] == '\t')) ++i;
    size_t end = i;
    while (end < glsl_.size() && continues_identifier(glsl_[end])) ++end;
    if (glsl_.substr(i, end - i) == "define") scan_.defines_macro = true;
  }

  size_t identifier(size_t i) {
    size_t end = i;
    while (end < glsl_.size() && continues_identifier(glsl_[end])) ++end;
    GlslWord word{std::string(glsl_.substr(i, end - i)), i};
    if (depth_ == 0 && parens_ == 0) {
      if (naming_) last_word_ = word.text;
      if (word.text == "layout") {
        statement_.layout_begin = i;
        in_layout_ = true;
      }
      statement_.words.push_back(word);
    }
    scan_.identifiers.push_back(std::move(word));
    return end;
  }

  void punctuation(char c, size_t i) {
    if (c == '(') {
      const bool after_layout = !statement_.words.empty() && statement_.words.back().text == "layout";
      if (parens_++ == 0 && !after_layout) statement_.has_parameters = true;
    } else if (c == ')') {
      parens_ = std::max(0, parens_ - 1);
      if (parens_ == 0 && in_layout_) {
        statement_.layout_end = i + 1;
        in_layout_ = false;
      }
    } else if (parens_ > 0) {
      return;
    } else if (c == '[') {
      statement_.has_brackets = true;
      close_name();
    } else if (c == ',') {
      close_name();
      naming_ = true;
    } else if (c == ';') {
      close_name();
      statement_.semicolon = i;
      if (statement_.layout_end == 0) statement_.layout_end = statement_.layout_begin;
      scan_.statements.push_back(std::move(statement_));
      restart();
    }
  }

  void close_name() {
    if (naming_ && !last_word_.empty()) statement_.names.push_back(last_word_);
    naming_ = false;
    last_word_.clear();
  }

  void restart() {
    statement_ = {};
    naming_ = true;
    in_layout_ = false;
    last_word_.clear();
  }

  size_t skip_to(size_t i, std::string_view end) {
    const size_t at = glsl_.find(end, i + 1);
    return at == std::string_view::npos ? glsl_.size() : at;
  }

  bool at_line_start(size_t i) const {
    while (i > 0 && (glsl_[i - 1] == ' ' || glsl_[i - 1] == '\t')) --i;
    return i == 0 || glsl_[i - 1] == '\n';
  }

  std::string_view glsl_;
  GlslScan scan_;
  int depth_ = 0, parens_ = 0;
  GlobalStatement statement_;
  bool naming_ = true;  // the current declarator's name is still open ('[' ends it)
  bool in_layout_ = false;
  std::string last_word_;
};

}  // namespace

bool GlobalStatement::has(std::string_view word) const {
  return std::any_of(words.begin(), words.end(), [&](const GlslWord& w) { return w.text == word; });
}

GlslScan scan_glsl(std::string_view glsl) { return Scanner(glsl).run(); }

}  // namespace shadelab::shader
