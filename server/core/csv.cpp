#include "core/csv.h"

#include <cstdio>

namespace shadelab {

std::string csv_cell(std::string_view text) {
  std::string cell(text);
  if (!cell.empty() && std::string_view("=+-@\t\r").find(cell.front()) != std::string_view::npos) cell.insert(0, 1, '\'');
  if (cell.find_first_of(",\"\r\n") == std::string::npos) return cell;
  std::string quoted = "\"";
  for (char c : cell) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

namespace {

std::string printable_except(std::string_view text, std::string_view kept) {
  std::string out;
  out.reserve(text.size());
  const auto escaped = [&](unsigned value) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "\\x%02X", value);
    out += buf;
  };
  for (size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if ((c < 0x20 || c == 0x7F) && kept.find(static_cast<char>(c)) == std::string_view::npos) {
      escaped(c);
    } else if (c == 0xC2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
               static_cast<unsigned char>(text[i + 1]) <= 0x9F) {
      escaped(static_cast<unsigned char>(text[++i]));  // U+0080..U+009F: C1 controls (CSI among them)
    } else {
      out += text[i];
    }
  }
  return out;
}

}  // namespace

std::string printable(std::string_view text) { return printable_except(text, ""); }
std::string printable_lines(std::string_view text) { return printable_except(text, "\n\t"); }

}  // namespace shadelab
