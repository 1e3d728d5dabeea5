#include "grade/value_reading.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

#include "gl/render_target.h"

namespace shadelab::grade {

namespace {

// More probes than this in a stage are not read: each is a run of main at every pixel.
constexpr size_t kMaxProbes = 64;

// One probe's float frames, every light's in order.
using ProbeFrames = std::vector<image::Image>;

struct Probed {
  repair::ProbedStage stage;
  std::vector<ProbeFrames> frames;  // per probe
};

// `lit` (one request per light) with its fragment stage probed, each probe drawn: none where the
// stage cannot be probed or a draw fails.
std::optional<Probed> drawn_probes(render::Renderer& renderer, const std::vector<render::RenderRequest>& lit, const scene::Mesh& mesh,
                                   const ValueCanvas& canvas) {
  if (lit.empty()) return std::nullopt;
  auto glsl = shader::unwrap(lit.front().fragment, shader::Stage::fragment);
  if (!glsl) return std::nullopt;
  auto stage = repair::probed_fragment(glsl->glsl);
  if (!stage || stage->probes.size() > kMaxProbes) return std::nullopt;
  std::vector<render::RenderRequest> requests;
  for (const auto& light : lit)
    for (size_t k = 0; k < stage->probes.size(); ++k) {
      render::RenderRequest r = light;
      r.fragment = {"value_probes.frag", stage->glsl};
      const double scale = static_cast<double>(canvas.size) / std::max(r.width, r.height);
      r.width = std::max(1, static_cast<int>(std::lround(r.width * scale)));
      r.height = std::max(1, static_cast<int>(std::lround(r.height * scale)));
      if (r.angles.empty()) r.degrees_per_frame *= static_cast<double>(r.frames) / canvas.frames;
      else r.angles.resize(static_cast<size_t>(canvas.frames), r.angles.back());
      r.frames = canvas.frames;
      r.msaa = 0;
      r.pixel_type = image::PixelType::f32;
      r.semantics = render::FloatSemantics::as_compiled;
      r.uniforms.push_back({repair::kProbeUniform, {static_cast<double>(k), 0, 0, 0}});
      requests.push_back(std::move(r));
    }
  std::vector<ProbeFrames> per_request(requests.size());
  const size_t chunk = static_cast<size_t>(std::max(1, gl::max_outputs()));
  for (size_t first = 0; first < requests.size(); first += chunk) {
    const std::vector<render::RenderRequest> some(requests.begin() + static_cast<std::ptrdiff_t>(first),
                                                  requests.begin() + static_cast<std::ptrdiff_t>(std::min(requests.size(), first + chunk)));
    auto drawn = renderer.render_together(some, mesh, [&](int i, int, const image::Image& f, bool) {
      per_request[first + static_cast<size_t>(i)].push_back(f);
    });
    if (!drawn) return std::nullopt;
  }
  // Requests are light by light, each light's probe by probe: a probe's frames are its every light's.
  Probed out{std::move(*stage), std::vector<ProbeFrames>(per_request.size() / lit.size())};
  for (size_t i = 0; i < per_request.size(); ++i)
    for (auto& f : per_request[i]) out.frames[i % out.frames.size()].push_back(std::move(f));
  return out;
}

const float* pixel(const image::Image& f, size_t i) { return reinterpret_cast<const float*>(f.bytes.data()) + 4 * i; }

using repair::same_value;

bool same_pixel(const float* p, const float* q) { return same_value(p[0], q[0]) && same_value(p[1], q[1]) && same_value(p[2], q[2]); }
bool ran(const float* p) { return p[3] > 1.5f; }

// Two probes' values at every pixel both drew: whether there are such pixels, whether the values
// are the same at each, and whether they differ at one where the two programs' outputs (`ends`)
// differ too.
struct Beside {
  bool compared = false, same = true, differs_visibly = false;
};

Beside beside(const ProbeFrames& a, const ProbeFrames& b, const ProbeFrames& a_end, const ProbeFrames& b_end) {
  Beside out;
  if (a.size() != b.size() || a.size() != a_end.size() || a.size() != b_end.size()) return {};
  for (size_t f = 0; f < a.size(); ++f) {
    const auto fits = [&](const image::Image& i) { return i.type == image::PixelType::f32 && i.width == a[f].width && i.height == a[f].height; };
    if (!fits(a[f]) || !fits(b[f]) || !fits(a_end[f]) || !fits(b_end[f])) return {};
    const size_t n = static_cast<size_t>(a[f].width) * static_cast<size_t>(a[f].height);
    for (size_t i = 0; i < n; ++i) {
      const float *p = pixel(a[f], i), *q = pixel(b[f], i);
      if (!ran(p) || !ran(q)) continue;
      out.compared = true;
      if (same_pixel(p, q)) continue;
      out.same = false;
      const float *pe = pixel(a_end[f], i), *qe = pixel(b_end[f], i);
      if (ran(pe) && ran(qe) && !same_pixel(pe, qe)) return out.differs_visibly = true, out;
    }
  }
  return out;
}

// The pixels both probes drew, `a`'s value beside `b`'s (`out` reused from pair to pair).
void samples_of(const ProbeFrames& a, const ProbeFrames& b, std::vector<repair::ValueSample>& out) {
  out.clear();
  for (size_t f = 0; f < a.size() && f < b.size(); ++f) {
    if (a[f].type != image::PixelType::f32 || b[f].type != a[f].type || b[f].width != a[f].width || b[f].height != a[f].height) continue;
    const size_t n = static_cast<size_t>(a[f].width) * static_cast<size_t>(a[f].height);
    for (size_t i = 0; i < n; ++i) {
      const float *p = pixel(a[f], i), *q = pixel(b[f], i);
      if (ran(p) && ran(q)) out.push_back({{p[0], p[1], p[2]}, {q[0], q[1], q[2]}});
    }
  }
}

}  // namespace

repair::ValueAgreement read_values(render::Renderer& renderer, const std::vector<render::RenderRequest>& student,
                                   const std::vector<render::RenderRequest>& reference, const scene::Mesh& mesh, const ValueCanvas& canvas) {
  repair::ValueAgreement out;
  if (student.size() != reference.size()) return out;
  const auto theirs = drawn_probes(renderer, student, mesh, canvas);
  if (!theirs) return out;
  const auto ours = drawn_probes(renderer, reference, mesh, canvas);
  if (!ours) return out;
  out.read = true;
  std::vector<repair::ValueSample> samples;
  for (const auto& s : theirs->frames) {
    std::vector<int> with, visibly;
    std::vector<repair::ValueChangeTo> changed;
    bool compared = false;
    for (size_t r = 0; r < ours->frames.size(); ++r) {
      const Beside b = beside(s, ours->frames[r], theirs->frames.back(), ours->frames.back());
      compared = compared || b.compared;
      if (b.compared && b.same) with.push_back(static_cast<int>(r));
      if (b.differs_visibly) visibly.push_back(static_cast<int>(r));
      if (!b.compared || b.same) continue;
      samples_of(s, ours->frames[r], samples);
      for (const auto change : repair::changes_between(samples)) changed.push_back({static_cast<int>(r), change});
    }
    out.changes.push_back(std::move(changed));
    out.agrees_with.push_back(std::move(with));
    out.differs_visibly.push_back(std::move(visibly));
    out.compared.push_back(compared);
  }
  return out;
}

}  // namespace shadelab::grade
