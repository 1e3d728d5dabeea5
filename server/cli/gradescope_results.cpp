#include "cli/gradescope_results.h"

#include <filesystem>
#include <iostream>

#include "cli/file_output.h"
#include "core/base64.h"
#include "core/csv.h"
#include "image/encode.h"
#include "image/png_decode.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string html_escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      default: out += c;
    }
  }
  return out;
}

// The heat map deflated as hard as zlib goes (level 9: ~25% smaller than the workers' fast level 1,
// ~0.15 s for the course's 1536 x 1536 grid), for one over the embedding limit: a page's saved
// frames, each a little off its angle, draw a busier map than ShadeLab's own did.
std::string harder(std::string png, size_t limit) {
  if (png.size() <= limit) return png;
  auto image = image::decode_png(png, 8192);
  auto again = image ? image::encode_png(*image, {.compression_level = 9}) : Expected<std::vector<std::uint8_t>>(image.error());
  if (again && again->size() < png.size()) png.assign(again->begin(), again->end());
  return png;
}

// A failed test's heat map written beside results.json, and embedded when small enough; `output`
// the test's text as shown.
void attach_heatmap(json& test, const HandInTest& t, const std::string& output, const HeatmapOutput& out) {
  if (t.heatmap_png.empty() || out.folder.empty()) return;
  const std::string png = harder(t.heatmap_png, out.embed_limit);
  const fs::path path = fs::path(out.folder) / (t.heatmap_name + ".png");
  if (auto written = write_file(path, png); !written) std::cerr << "autograde: " << written.error().message << "\n";
  if (png.size() > out.embed_limit) {
    test["output"] = output + "difference heat map: " + path.string() + "\n";
    return;
  }
  test["output_format"] = "html";
  test["output"] = "<pre>" + html_escape(output) +
                   "</pre><p>Where your frames differ from the reference (brighter: further off):</p>"
                   "<img alt=\"difference heat map\" style=\"max-width:100%\" src=\"data:image/png;base64," + base64_encode(png) + "\">";
}

// Every text may hold a student's file name: its control characters are shown, not obeyed
// (core/csv.h), in Gradescope's page as on a TA's terminal.
json test_json(const HandInTest& t, const HeatmapOutput& heatmaps) {
  const std::string output = printable_lines(t.output);
  json test = {{"name", printable(t.name)}, {"score", t.score}, {"max_score", t.max_score}, {"status", t.pass ? "passed" : "failed"},
               {"visibility", "visible"}, {"output", output}};
  if (!t.extra_data.is_null()) test["extra_data"] = t.extra_data;
  attach_heatmap(test, t, output, heatmaps);
  return test;
}

}  // namespace

json gradescope_results(const HandInResults& r, const HeatmapOutput& heatmaps) {
  json tests = json::array();
  for (const auto& t : r.tests) tests.push_back(test_json(t, heatmaps));
  return {{"score", r.score}, {"execution_time", r.seconds}, {"output", printable_lines(r.summary)}, {"tests", tests}};
}

}  // namespace shadelab::cli
