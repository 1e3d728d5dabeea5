#include "grade/render_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <unordered_map>

#include "core/words.h"

namespace shadelab::grade {

namespace {


// The share of pixels more than 8/255 off the image's commonest colour (any channel, alpha too).
double off_commonest(const image::Image& im) {
  const size_t n = static_cast<size_t>(im.width) * im.height;
  if (n == 0) return 0;
  std::unordered_map<std::uint32_t, size_t> counts;
  const auto colour = [&](size_t i) {
    std::uint32_t c;
    std::memcpy(&c, &im.bytes[i * 4], 4);
    return c;
  };
  for (size_t i = 0; i < n; ++i) ++counts[colour(i)];
  const std::uint32_t commonest =
      std::max_element(counts.begin(), counts.end(), [](const auto& a, const auto& b) { return a.second < b.second; })->first;
  const std::uint8_t* c = reinterpret_cast<const std::uint8_t*>(&commonest);
  size_t off = 0;
  for (size_t i = 0; i < n; ++i) {
    int d = 0;
    for (int k = 0; k < 4; ++k) d = std::max(d, std::abs(static_cast<int>(im.bytes[i * 4 + static_cast<size_t>(k)]) - c[k]));
    off += d > 8;
  }
  return static_cast<double>(off) / static_cast<double>(n);
}

}  // namespace

std::string RenderCheck::facts_line() const {
  std::string out;
  for (const auto& f : facts) out += (out.empty() ? "" : "; ") + f.name + ": " + (f.holds ? "yes" : "no") + " (" + f.detail + ")";
  return out;
}

RenderCheck check_render(const image::Image& im, const RenderCheckOptions& options) {
  RenderCheck r;
  r.facts.push_back({"a PNG", true, std::to_string(im.width) + " x " + std::to_string(im.height)});
  const double off = off_commonest(im);
  r.facts.push_back({"not blank", off >= options.blank, percent(off, 1) + " of the pixels differ from the commonest colour"});
  r.pass = std::all_of(r.facts.begin(), r.facts.end(), [](const RenderFact& f) { return f.holds; });
  return r;
}

std::string render_check_leaves_out(int objects) {
  return "That it shows " + std::to_string(objects) +
         " objects on a plane, each fully within the image, with different materials, is the TA's to judge: ShadeLab cannot tell "
         "objects from the floor in a picture without guessing.";
}

}  // namespace shadelab::grade
