#include "shader/invariant_outputs.h"

#include <algorithm>
#include <cctype>
#include <vector>

namespace shadelab::shader {

namespace {

bool starts_identifier(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool continues_identifier(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// One global statement as it is read: its identifiers at parenthesis depth 0 (a layout's are
// inside parentheses, a prototype's parameters too) and, per top-level comma, the declared name.
struct Statement {
  std::vector<std::string> words;
  std::vector<std::string> names;  // the name of each declarator, once its segment has one
  bool naming = true;              // the current declarator's name is still open ('[' ends it)
  bool has_parameters = false;     // a '(' not after `layout`: a function, not a declaration

  bool declares_output() const {
    const auto has = [&](std::string_view w) { return std::find(words.begin(), words.end(), w) != words.end(); };
    return has("out") && !has("invariant") && !has_parameters && !names.empty();
  }
};

class Scanner {
 public:
  Scanner(std::string_view glsl, Stage stage) : glsl_(glsl), stage_(stage) {}

  std::string run() {
    for (size_t i = 0; i < glsl_.size();) i = step(i);
    out_.append(glsl_.substr(copied_));
    return out_;
  }

 private:
  size_t step(size_t i) {
    const char c = glsl_[i];
    if (glsl_.substr(i, 2) == "//") return skip_to(i, "\n");
    if (glsl_.substr(i, 2) == "/*") return skip_to(i, "*/") + 2;
    if (c == '#' && at_line_start(i)) return skip_to(i, "\n");
    if (starts_identifier(c)) return identifier(i);
    if (c == '{' || c == '}') {
      depth_ += c == '{' ? 1 : -1;
      statement_ = {};
    } else if (depth_ == 0) {
      punctuation(c, i);
    }
    return i + 1;
  }

  size_t identifier(size_t i) {
    size_t end = i;
    while (end < glsl_.size() && continues_identifier(glsl_[end])) ++end;
    if (depth_ == 0 && parens_ == 0) {
      std::string word(glsl_.substr(i, end - i));
      if (statement_.naming) last_word_ = word;
      statement_.words.push_back(std::move(word));
    }
    return end;
  }

  void punctuation(char c, size_t i) {
    if (c == '(') {
      if (parens_++ == 0 && (statement_.words.empty() || statement_.words.back() != "layout")) statement_.has_parameters = true;
    } else if (c == ')') {
      parens_ = std::max(0, parens_ - 1);
    } else if (parens_ > 0) {
      return;
    } else if (c == '[') {
      close_name();
    } else if (c == ',') {
      close_name();
      statement_.naming = true;
    } else if (c == ';') {
      close_name();
      if (statement_.declares_output()) insert_after(i, statement_.names);
      statement_ = {};
    }
  }

  void close_name() {
    if (statement_.naming && !last_word_.empty()) statement_.names.push_back(last_word_);
    statement_.naming = false;
    last_word_.clear();
  }

  void insert_after(size_t semicolon, std::vector<std::string> names) {
    if (stage_ == Stage::vertex && !position_done_) names.push_back("gl_Position");
    position_done_ = true;
    out_.append(glsl_.substr(copied_, semicolon + 1 - copied_));
    copied_ = semicolon + 1;
    out_ += " invariant ";
    for (size_t k = 0; k < names.size(); ++k) out_ += (k ? ", " : "") + names[k];
    out_ += ";";
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
  Stage stage_;
  std::string out_;
  size_t copied_ = 0;
  int depth_ = 0, parens_ = 0;
  Statement statement_;
  std::string last_word_;
  bool position_done_ = false;
};

}  // namespace

std::string with_invariant_outputs(std::string_view glsl, Stage stage) { return Scanner(glsl, stage).run(); }

}  // namespace shadelab::shader
