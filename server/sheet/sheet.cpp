#include "sheet/sheet.h"

#include <cstdio>

namespace shadelab::sheet {

std::string section_title(const std::string& checkpoint) {
  if (checkpoint == "smooth") return "Smooth shading";
  if (checkpoint == "gouraud") return "Gouraud shading (lighting in the vertex shader), with its code";
  if (checkpoint == "diffuse") return "Phong reflection: ambient + diffuse";
  if (checkpoint == "specular") return "Phong reflection: ambient + diffuse + specular, with its code";
  return checkpoint;
}

std::string verdict(const grade::Report& report) {
  char score[64];
  std::snprintf(score, sizeof score, "%g / %g", report.score, report.max_score);
  const std::string why = report.messages.empty() ? (report.pass ? "passes" : "does not pass") : report.messages.front();
  return std::string(score) + ": " + why;
}

std::set<int> lines_pointed_at(const grade::Report& report, const std::string& file_name) {
  const size_t slash = file_name.find_last_of('/');
  const std::string base = slash == std::string::npos ? file_name : file_name.substr(slash + 1);
  std::set<int> lines;
  for (const auto& d : report.diagnostics)
    if (d.line > 0 && (d.file == file_name || d.file == base)) lines.insert(d.line);
  return lines;
}

namespace {
// The length of the UTF-8 sequence at `s[i]`, or 0 when it is not a valid one.
size_t utf8_length(const std::string& s, size_t i) {
  const auto c = static_cast<unsigned char>(s[i]);
  const size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(s[i + k]) & 0xc0) != 0x80) return 0;
  return n;
}
}  // namespace

std::string printable(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '\t') {
      out += "    ";
      ++i;
      continue;
    }
    const size_t n = utf8_length(text, i);
    const bool control = n == 1 && (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) && c != '\n';
    if (n == 0 || control) {
      if (c != '\r') out += '?';
      i += n == 0 ? 1 : n;
      continue;
    }
    out.append(text, i, n);
    i += n;
  }
  return out;
}

}  // namespace shadelab::sheet
