#include "sheet/sheet_html.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "core/base64.h"

namespace shadelab::sheet {

namespace {

std::string escape(const std::string& text) {
  std::string out;
  for (const char c : printable(text)) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

constexpr char kStyle[] = R"(body{font-family:"DejaVu Sans",sans-serif;max-width:60em;margin:2em auto;color:#1a1a1a}
section{margin-bottom:3em}img{width:100%}.pass{color:#0d7326}.fail{color:#b31a1a}.note{color:#737373}
pre{font:0.8em "DejaVu Sans Mono",monospace;white-space:pre-wrap;border-left:3px solid #ddd;padding-left:.5em}
.n{color:#737373;user-select:none;display:inline-block;width:3em}.marked{background:#ffed99}.marked .n{color:#b31a1a}
.render{position:relative}.box{position:absolute;border:2px solid;font-size:.75em;font-weight:bold;padding:0 .2em}
.box.in{border-color:#0d7326;color:#0d7326}.box.out{border-color:#b31a1a;color:#b31a1a})";

void code(std::ostringstream& out, const CodeListing& listing) {
  out << "<h3>" << escape(listing.file_name) << "</h3>\n<pre>";
  std::istringstream lines(listing.text);
  int number = 0;
  for (std::string line; std::getline(lines, line);) {
    ++number;
    const bool marked = listing.marked_lines.count(number) > 0;
    out << "<span" << (marked ? " class=\"marked\"" : "") << "><span class=\"n\">" << number << "</span>" << escape(line)
        << "</span>\n";
  }
  out << "</pre>\n";
}

void checkpoint(std::ostringstream& out, const CheckpointSection& s, size_t index) {
  out << "<section id=\"" << escape(s.checkpoint) << "\">\n<h2>" << index << ". " << escape(s.title)
      << "</h2>\n<p class=\"" << section_class(s) << "\">" << escape(section_verdict(s)) << "</p>\n";
  // Below the score: the code's report when it was graded, else what was handed in.
  for (size_t k = 0; k < s.report.messages.size() && k < 4; ++k)
    out << "<p class=\"note\">" << escape(s.report.messages[k]) << "</p>\n";
  for (const auto& line : frames_lines(s))
    out << "<p class=\"" << (s.frames_report && s.frames_report->pass ? "pass" : "fail") << "\">" << escape(line) << "</p>\n";
  if (!s.saved_grid_png.empty())
    out << "<p class=\"note\">the frames the student saved</p>\n<img alt=\"3x3 grid of the saved " << escape(s.checkpoint)
        << " frames\" src=\"data:image/png;base64," << base64_encode(s.saved_grid_png) << "\">\n";
  if (s.grid_png.empty())
    out << "<p class=\"note\">" << (s.graded ? "(no grid: the shaders did not render)" : "(no grid)") << "</p>\n";
  else
    out << "<p class=\"note\">" << escape(s.grid_caption) << "</p>\n<img alt=\"3x3 grid of " << escape(s.checkpoint)
        << "\" src=\"data:image/png;base64," << base64_encode(s.grid_png) << "\">\n";
  for (const auto& listing : s.code) code(out, listing);
  out << "</section>\n";
}

void handed_in(std::ostringstream& out, const ImageSection& s) {
  out << "<section class=\"image\">\n<h2>" << escape(s.title) << " <span class=\"note\">(" << escape(s.file) << ")</span></h2>\n";
  if (s.check && s.problem.empty()) out << "<p class=\"" << (s.check->verdict.pass ? "pass" : "fail") << "\">" << escape(image_verdict(*s.check)) << "</p>\n";
  if (!s.problem.empty()) out << "<p class=\"fail\">" << escape(s.problem) << "</p>\n";
  else out << "<img alt=\"" << escape(s.title) << "\" src=\"data:image/png;base64," << base64_encode(s.png) << "\">\n";
  out << "</section>\n";
}

// The render with each object's framing box placed in percentages of the image (clipped by it).
void scene(std::ostringstream& out, const SceneSection& s) {
  out << "<section class=\"scene\">\n<h2>Blender: " << escape(s.name);
  if (!s.error.empty()) {
    out << "</h2>\n<p class=\"fail\">does not render: " << escape(s.error) << "</p>\n</section>\n";
    return;
  }
  const bool all_in = !s.framing.empty() && std::all_of(s.framing.begin(), s.framing.end(), [](const auto& f) { return f.fully_visible || !f.drawn; });
  out << " (lens " << s.lens_mm << " mm, " << s.width << " x " << s.height << ")</h2>\n<p class=\"" << (all_in ? "pass" : "fail") << "\">"
      << escape(framing_verdict(s)) << "</p>\n<div class=\"render\" style=\"overflow:hidden\"><img alt=\"" << escape(s.name)
      << "\" src=\"data:image/png;base64," << base64_encode(s.png) << "\">";
  char style[200];
  for (const auto& f : s.framing) {
    if (!f.box || s.width <= 0 || s.height <= 0) continue;
    std::snprintf(style, sizeof style, "left:%.3f%%;top:%.3f%%;width:%.3f%%;height:%.3f%%", 100 * f.box->min.x / s.width,
                  100 * f.box->min.y / s.height, 100 * (f.box->max.x - f.box->min.x) / s.width, 100 * (f.box->max.y - f.box->min.y) / s.height);
    out << "<div class=\"box " << (f.fully_visible ? "in" : "out") << "\" style=\"" << style << "\">" << escape(f.name) << "</div>";
  }
  out << "</div>\n<ul>\n";
  for (const auto& f : s.framing) out << "<li>" << escape(framing_line(f)) << "</li>\n";
  for (const auto& [name, material] : s.materials) out << "<li class=\"note\">" << escape(name + ": " + material_line(material)) << "</li>\n";
  out << "</ul>\n</section>\n";
}

// Each question with the answer under it in the student's notebook, the colours it gives rendered.
void answered(std::ostringstream& out, const Sheet& sheet) {
  out << "<section id=\"questions\">\n<h2>Questions</h2>\n";
  if (!sheet.notebook_note.empty()) out << "<p class=\"note\">" << escape(sheet.notebook_note) << "</p>\n";
  out << "<ol>\n";
  for (const auto& a : sheet.answered) {
    out << "<li><p class=\"note\">" << escape(a.question) << "</p>\n";
    if (!a.missing.empty()) out << "<p class=\"note\">" << escape(a.missing) << "</p>\n";
    std::istringstream paragraphs(a.answer);
    for (std::string p; std::getline(paragraphs, p);)
      if (!p.empty()) out << "<p>" << escape(p) << "</p>\n";
    if (!a.render_caption.empty()) out << "<p class=\"note\">" << escape(a.render_caption) << "</p>\n";
    if (!a.render_png.empty())
      out << "<img style=\"width:50%\" alt=\"the bunny in the answer's colours\" src=\"data:image/png;base64," << base64_encode(a.render_png) << "\">\n";
    out << "</li>\n";
  }
  out << "</ol>\n</section>\n";
}

}  // namespace

std::string render_html(const Sheet& sheet) {
  std::ostringstream out;
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << escape(sheet.title)
      << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n<h1>" << escape(sheet.title) << "</h1>\n";
  for (size_t i = 0; i < sheet.checkpoints.size(); ++i) checkpoint(out, sheet.checkpoints[i], i + 1);
  if (!sheet.answered.empty()) {
    answered(out, sheet);
  } else if (!sheet.questions.empty() || !sheet.answers.empty()) {
    out << "<section id=\"questions\">\n<h2>Questions</h2>\n";
    if (!sheet.notebook_problem.empty()) out << "<p class=\"fail\">" << escape(sheet.notebook_name) << ": " << escape(sheet.notebook_problem) << "</p>\n";
    out << "<ol>\n";
    for (const auto& q : sheet.questions) out << "<li>" << escape(q) << "</li>\n";
    out << "</ol>\n<h3>Answers</h3>\n";
    if (sheet.answers.empty()) out << "<p class=\"note\">(no answers given)</p>\n";
    std::istringstream paragraphs(sheet.answers);
    for (std::string p; std::getline(paragraphs, p);)
      if (!p.empty()) out << "<p>" << escape(p) << "</p>\n";
    out << "</section>\n";
  }
  for (const auto& s : sheet.images) handed_in(out, s);
  for (const auto& s : sheet.scenes) scene(out, s);
  out << "</body>\n</html>\n";
  return out.str();
}

}  // namespace shadelab::sheet
