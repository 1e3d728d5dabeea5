#include "sheet/sheet.h"

#include "core/words.h"

#include <algorithm>
#include <cstdio>

namespace shadelab::sheet {

std::string verdict(const grade::Report& report) {
  char score[64];
  std::snprintf(score, sizeof score, "%g / %g", report.score, report.max_score);
  const std::string why = report.messages.empty() ? (report.pass ? "passes" : "does not pass") : report.messages.front();
  return std::string(score) + ": " + why;
}

std::string image_verdict(const grade::ImageCheck& check) {
  char score[64];
  std::snprintf(score, sizeof score, "%g / %g", check.score(), check.points);
  return std::string(score) + (check.points == 0 ? " (for the TA)" : "") + ": " + check.text();
}

std::string section_verdict(const CheckpointSection& s) { return s.score.verdict(); }

std::string_view section_class(const CheckpointSection& s) {
  if (s.score.max_score > 0 && s.score.score >= s.score.max_score - 1e-9) return "pass";
  for (const auto& t : s.score.tests)
    if (t.report) return "fail";
  return "note";
}

std::vector<std::string> frames_lines(const CheckpointSection& s) {
  std::vector<std::string> out;
  if (!s.frames_report) return out;
  const grade::Report& r = *s.frames_report;
  double lo = 1e9, hi = -1e9;
  for (size_t k = 1; k < r.frames.size(); ++k)
    if (r.frames[k].lag_degrees) lo = std::min(lo, *r.frames[k].lag_degrees), hi = std::max(hi, *r.frames[k].lag_degrees);
  char lags[96] = "";
  if (hi >= lo && hi < 0.005) std::snprintf(lags, sizeof lags, " (drawn at their nominal angles)");
  else if (hi >= lo) std::snprintf(lags, sizeof lags, " (drawn %.2f to %.2f degrees behind their nominal angles)", lo, hi);
  for (const auto& flag : r.flags) out.push_back("FLAGGED FOR THE TA: " + flag.message);
  out.push_back("saved frames: " + verdict(r) + lags);
  if (s.match_report) out.push_back("saved frames against the code: " + (s.match_report->messages.empty() ? verdict(*s.match_report) : s.match_report->messages[0]));
  return out;
}

std::set<int> lines_pointed_at(const grade::Report& report, const std::string& file_name) {
  const size_t slash = file_name.find_last_of('/');
  const std::string base = slash == std::string::npos ? file_name : file_name.substr(slash + 1);
  std::set<int> lines;
  for (const auto& d : report.diagnostics)
    if (d.line > 0 && (d.file == file_name || d.file == base)) lines.insert(d.line);
  return lines;
}

std::string framing_verdict(const SceneSection& scene) {
  std::vector<std::string> out_of_frame;
  for (const auto& f : scene.framing)
    if (f.drawn && !f.fully_visible) out_of_frame.push_back(f.name);
  if (scene.framing.empty()) return "no framing report";
  if (out_of_frame.empty())
    return scene.framing.size() == 2 ? "both objects fully in the image" : "every object fully in the image";
  return "not fully in the image: " + comma_list(out_of_frame);
}

std::string framing_line(const scene_render::ObjectFraming& f) {
  char text[160];
  if (!f.drawn) return f.name + ": not drawn (zero scale)";
  if (f.behind_camera) return f.name + ": behind the camera";
  std::snprintf(text, sizeof text, "%s, %.0f%% of it in frame, covers %.1f%% of the image",
                f.fully_visible ? "fully in the image" : "cut by the frame", 100 * f.fraction_in_frame, 100 * f.image_coverage);
  return f.name + ": " + text;
}

std::string material_line(const scene::Material& m) {
  char text[200];
  std::snprintf(text, sizeof text, "base colour (%.2f, %.2f, %.2f), metallic %.2f, roughness %.2f, specular %.2f", m.base_color.x,
                m.base_color.y, m.base_color.z, m.metallic, m.roughness, m.specular);
  std::string out = text;
  if (m.subsurface > 0) {
    std::snprintf(text, sizeof text, ", subsurface %.2f (colour %.2f, %.2f, %.2f)", m.subsurface, m.subsurface_color.x,
                  m.subsurface_color.y, m.subsurface_color.z);
    out += text;
  }
  if (m.emission != glm::dvec3(0.0)) {
    std::snprintf(text, sizeof text, ", emission (%.2f, %.2f, %.2f) x %.2f", m.emission.x, m.emission.y, m.emission.z, m.emission_strength);
    out += text;
  }
  return out;
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
