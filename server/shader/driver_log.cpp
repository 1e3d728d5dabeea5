#include "shader/driver_log.h"

#include <charconv>
#include <cctype>
#include <string_view>
#include <sstream>

namespace shadelab::shader {

namespace {
struct Located {
  int line = 0, column = 0;
  std::string severity, message;
};

// A line or column number; 0 (unknown) when it does not fit an int (a driver's log is read,
// not trusted: std::stoi would throw).
int number(std::string_view digits) {
  int value = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  return error == std::errc() && end == digits.data() + digits.size() ? value : 0;
}

// A left-to-right reader of one log line. It replaced std::regex, whose libstdc++ matcher recurses
// once per character: a message quoting a student's 60 KB identifier overflowed the worker's
// stack (tests/fuzz/regressions/driver_log).
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}
  // Skips white space; how much there was.
  size_t spaces() { return span([](unsigned char c) { return std::isspace(c) != 0; }).size(); }
  bool literal(std::string_view word) {
    if (text_.substr(at_, word.size()) != word) return false;
    at_ += word.size();
    return true;
  }
  std::string_view digits() { return span([](unsigned char c) { return std::isdigit(c) != 0; }); }
  void word() { span([](unsigned char c) { return std::isalnum(c) != 0 || c == '_'; }); }
  // One of `words` (e.g. error or warning) right here, or "".
  std::string_view one_of(std::initializer_list<std::string_view> words) {
    for (const auto w : words)
      if (literal(w)) return w;
    return {};
  }
  std::string_view rest() {
    spaces();
    return text_.substr(at_);
  }

 private:
  template <class Pred>
  std::string_view span(Pred pred) {
    const size_t begin = at_;
    while (at_ < text_.size() && pred(static_cast<unsigned char>(text_[at_]))) ++at_;
    return text_.substr(begin, at_ - begin);
  }
  std::string_view text_;
  size_t at_ = 0;
};

// Mesa: "0:12(5): error: message" (also "0:12(5): preprocessor error: ...").
bool mesa(LineReader r, Located& out) {
  r.spaces();
  if (r.digits().empty() || !r.literal(":")) return false;
  const auto line = r.digits();
  if (line.empty() || !r.literal("(")) return false;
  const auto column = r.digits();
  if (column.empty() || !r.literal("):")) return false;
  r.spaces();
  if (r.literal("preprocessor") && r.spaces() == 0) return false;
  const auto severity = r.one_of({"error", "warning"});
  if (severity.empty() || !r.literal(":")) return false;
  out = {number(line), number(column), std::string(severity), std::string(r.rest())};
  return true;
}

// NVIDIA: "0(12) : error C0000: message".
bool nvidia(LineReader r, Located& out) {
  r.spaces();
  if (r.digits().empty() || !r.literal("(")) return false;
  const auto line = r.digits();
  if (line.empty() || !r.literal(")")) return false;
  r.spaces();
  if (!r.literal(":")) return false;
  r.spaces();
  const auto severity = r.one_of({"error", "warning"});
  if (severity.empty()) return false;
  r.spaces();
  r.word();
  if (!r.literal(":")) return false;
  out = {number(line), 0, std::string(severity), std::string(r.rest())};
  return true;
}

// ANGLE: "ERROR: 0:12: message".
bool angle(LineReader r, Located& out) {
  r.spaces();
  const auto severity = r.one_of({"ERROR", "WARNING"});
  if (severity.empty() || !r.literal(":")) return false;
  r.spaces();
  if (r.digits().empty() || !r.literal(":")) return false;
  const auto line = r.digits();
  if (line.empty() || !r.literal(":")) return false;
  out = {number(line), 0, severity == "ERROR" ? "error" : "warning", std::string(r.rest())};
  return true;
}

// No location: "error: message".
bool bare(LineReader r, Located& out) {
  r.spaces();
  const auto severity = r.one_of({"error", "warning"});
  if (severity.empty() || !r.literal(":")) return false;
  out = {0, 0, std::string(severity), std::string(r.rest())};
  return true;
}

bool parse_line(std::string_view text, Located& out) {
  if (!text.empty() && text.back() == '\r') text.remove_suffix(1);  // a CRLF log
  const LineReader r(text);
  return mesa(r, out) || nvidia(r, out) || angle(r, out) || bare(r, out);
}
}  // namespace

std::vector<Diagnostic> parse_driver_log(const std::string& log, std::string_view stage, const std::string& file_name,
                                         const UnwrappedSource* source) {
  std::vector<Diagnostic> out;
  std::istringstream lines(log);
  std::string text;
  while (std::getline(lines, text)) {
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    Located at;
    if (!parse_line(text, at)) {
      // A continuation of the previous message (drivers wrap long ones), or a line of its own.
      if (!out.empty()) {
        out.back().message += "\n" + text;
      } else {
        out.push_back(Diagnostic{std::string(stage), file_name, 0, 0, "error", text});
      }
      continue;
    }
    Diagnostic d{std::string(stage), file_name, 0, 0, at.severity, at.message};
    if (source && at.line > 0) {
      const LineOrigin where = source->locate(at.line, at.column);
      d.line = where.file_line;
      d.column = where.file_column;
    }
    out.push_back(std::move(d));
  }
  return out;
}

}  // namespace shadelab::shader
