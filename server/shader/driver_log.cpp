#include "shader/driver_log.h"

#include <charconv>
#include <regex>
#include <sstream>

namespace shadelab::shader {

namespace {
struct Located {
  int line = 0, column = 0;
  std::string severity, message;
};

// A line or column number; 0 (unknown) when it does not fit an int (a driver's log is read,
// not trusted: std::stoi would throw).
int number(const std::ssub_match& digits) {
  int value = 0;
  const std::string text = digits.str();
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size() ? value : 0;
}

bool parse_line(const std::string& text, Located& out) {
  static const std::regex mesa(R"(^\s*\d+:(\d+)\((\d+)\):\s*(?:preprocessor\s+)?(error|warning):\s*(.*)$)");
  static const std::regex nvidia(R"(^\s*\d+\((\d+)\)\s*:\s*(error|warning)\s*\w*:\s*(.*)$)");
  static const std::regex angle(R"(^\s*(ERROR|WARNING):\s*\d+:(\d+):\s*(.*)$)");
  static const std::regex bare(R"(^\s*(error|warning):\s*(.*)$)");
  std::smatch m;
  if (std::regex_match(text, m, mesa)) {
    out = {number(m[1]), number(m[2]), m[3], m[4]};
  } else if (std::regex_match(text, m, nvidia)) {
    out = {number(m[1]), 0, m[2], m[3]};
  } else if (std::regex_match(text, m, angle)) {
    out = {number(m[2]), 0, m[1] == "ERROR" ? "error" : "warning", m[3]};
  } else if (std::regex_match(text, m, bare)) {
    out = {0, 0, m[1], m[2]};
  } else {
    return false;
  }
  return true;
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
