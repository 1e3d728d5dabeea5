// What accuracy costs in time: sweeps the knobs that trade one for the other on the render core,
// each point measured against a double-precision ray-cast reference of an analytic sphere shaded
// by the same Phong model (server/reference), and timed warm (median and spread over repeats).
//
//   build/bench/accuracy_bench [out_dir=docs] [repeats=7]
// writes out_dir/accuracy.csv, accuracy.md (the table) and accuracy.svg (error vs time, Pareto
// front marked). The baseline: per-fragment Phong (the course's specular reference), a 64-segment
// sphere, 4x MSAA, no supersampling, the course's canvas (512 x 512), highp. Each series changes one knob.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "canonical_job.h"
#include "course/reference_sphere.h"
#include "reference/phong_raycast.h"
#include "render/renderer.h"
#include "scene/uv_sphere.h"

namespace {

using namespace shadelab;
using Clock = std::chrono::steady_clock;

struct Point {
  std::string series, label;
  std::string shading = "phong";
  int segments = 64, msaa = 4, supersample = 1, width = 0, height = 0;  // 0: the course's canvas
  bool mediump = false;
};

struct Measured {
  Point p;
  double median_ms = 0, min_ms = 0, max_ms = 0, rmse = 0, max_error = 0;
  size_t triangles = 0;
  int samples = 0;  // what the driver gave (llvmpipe rounds a request for 2 up to 4)
  std::string note;
};

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
  return s;
}

// Lighting per vertex, the colour interpolated: Gouraud shading of the same Phong model.
const char* kGouraudVertex = R"(#version 300 es
precision highp float;
in vec4 aVertexPosition;
in vec4 aVertexNormal;
uniform mat4 uMeshToWorldMatrix;
uniform mat4 uMeshToWorldRotMatrix;
uniform mat4 uWorldToClipSpaceMatrix;
uniform vec4 uAmbientColor;
uniform vec4 uDiffuseColor;
uniform vec4 uSpecularColor;
uniform vec3 uLightPosition;
uniform vec4 uLightColor;
out vec4 vColor;
void main(void) {
    vec4 p = uMeshToWorldMatrix * aVertexPosition;
    vec3 N = normalize((uMeshToWorldRotMatrix * aVertexNormal).xyz);
    vec3 L = normalize(uLightPosition - p.xyz);
    float NdotL = dot(N, L);
    vec4 color = uAmbientColor + uDiffuseColor * uLightColor * max(0.0, NdotL);
    if (NdotL > 0.0) color += uSpecularColor * uLightColor * pow(max(0.0, dot(normalize(-p.xyz), reflect(-L, N))), ALPHA);
    vColor = color;
    gl_Position = uWorldToClipSpaceMatrix * p;
}
)";
const char* kGouraudFragment = R"(#version 300 es
precision highp float;
in vec4 vColor;
out vec4 fragColor;
void main(void) { fragColor = vColor; }
)";

// A GLSL float literal of the course's exponent.
std::string alpha_literal() {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(6);
  s << bench::canonical_course().specular_exponent();
  return s.str();
}

render::RenderRequest request_for(const Point& p) {
  const auto& course = bench::canonical_course();
  const auto& phong = *course.preset("specular");
  render::RenderRequest r = course.render_request(phong.vertex, phong.fragment);
  if (p.shading == "flat") {
    r.vertex.text = replace_all(r.vertex.text, "out vec3 vNormal;", "flat out vec3 vNormal;");
    r.fragment.text = replace_all(r.fragment.text, "in vec3 vNormal;", "flat in vec3 vNormal;");
  } else if (p.shading == "gouraud") {
    r.vertex = {"gouraud_vert.glsl", replace_all(kGouraudVertex, "ALPHA", alpha_literal())};
    r.fragment = {"gouraud_frag.glsl", kGouraudFragment};
  }
  if (p.mediump)
    for (auto* s : {&r.vertex.text, &r.fragment.text}) *s = replace_all(*s, "precision highp float;", "precision mediump float;");
  r.width = p.width * p.supersample;
  r.height = p.height * p.supersample;
  r.frames = 1;
  r.msaa = p.msaa;
  return r;
}

// Box-filters an RGBA8 frame k x k down, into floats in [0, 1].
std::vector<double> downsample(const image::Image& f, int k) {
  const int w = f.width / k, h = f.height / k;
  std::vector<double> out(static_cast<size_t>(w) * h * 3, 0.0);
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x)
      for (int c = 0; c < 3; ++c)
        out[(static_cast<size_t>(y / k) * w + x / k) * 3 + c] += f.bytes[(static_cast<size_t>(y) * f.width + x) * 4 + c] / (255.0 * k * k);
  return out;
}

void errors(const std::vector<double>& gl, const image::Image& ref, double& rmse, double& max_error) {
  double sum = 0;
  max_error = 0;
  for (size_t i = 0; i < gl.size(); ++i) {
    float v;
    std::memcpy(&v, ref.bytes.data() + (i / 3) * 16 + (i % 3) * 4, 4);
    const double d = std::abs(gl[i] - v);
    sum += d * d;
    max_error = std::max(max_error, d);
  }
  rmse = std::sqrt(sum / static_cast<double>(gl.size()));
}

std::string fmt(double v, int precision = 2) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(precision);
  s << v;
  return s.str();
}

void write_svg(const std::vector<Measured>& ms, const std::vector<bool>& front, const std::string& path) {
  const double W = 760, H = 480, L = 70, R = 200, T = 20, B = 50;
  double tmax = 0, emin = 1e9, emax = 0;
  for (const auto& m : ms)
    if (m.note.empty()) tmax = std::max(tmax, m.median_ms), emin = std::min(emin, m.rmse), emax = std::max(emax, m.rmse);
  const double lo = std::log10(emin) - 0.1, hi = std::log10(emax) + 0.1;
  const auto X = [&](double t) { return L + t / (tmax * 1.05) * (W - L - R); };
  const auto Y = [&](double e) { return T + (hi - std::log10(e)) / (hi - lo) * (H - T - B); };
  const std::map<std::string, std::string> colour = {{"shading", "#e8a33d"}, {"density", "#4ea3e8"}, {"msaa", "#7ac74f"},
                                                     {"supersampling", "#d35fb7"}, {"resolution", "#e85d4e"}, {"precision", "#9aa0b4"}};
  std::ofstream svg(path);
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H << "' font-family='sans-serif' font-size='11'>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n"
      << "<line x1='" << L << "' y1='" << H - B << "' x2='" << W - R << "' y2='" << H - B << "' stroke='black'/>\n"
      << "<line x1='" << L << "' y1='" << T << "' x2='" << L << "' y2='" << H - B << "' stroke='black'/>\n"
      << "<text x='" << (L + W - R) / 2 << "' y='" << H - 12 << "' text-anchor='middle'>time per frame, ms (median)</text>\n"
      << "<text x='14' y='" << (T + H - B) / 2 << "' transform='rotate(-90 14 " << (T + H - B) / 2
      << ")' text-anchor='middle'>RMSE against the ray-cast reference (log)</text>\n";
  for (int k = 0; k <= 4; ++k) {
    const double t = tmax * 1.05 * k / 4;
    svg << "<text x='" << X(t) << "' y='" << H - B + 14 << "' text-anchor='middle'>" << fmt(t, 1) << "</text>\n";
  }
  for (int e = static_cast<int>(std::floor(lo)); e <= static_cast<int>(std::ceil(hi)); ++e)
    for (double m : {1.0, 2.0, 5.0}) {
      const double v = m * std::pow(10.0, e);
      if (std::log10(v) < lo || std::log10(v) > hi) continue;
      svg << "<text x='" << L - 6 << "' y='" << Y(v) + 4 << "' text-anchor='end'>" << v << "</text>\n"
          << "<line x1='" << L << "' y1='" << Y(v) << "' x2='" << W - R << "' y2='" << Y(v) << "' stroke='#eee'/>\n";
    }
  // The Pareto front: no other point is both faster and more accurate.
  std::vector<const Measured*> f;
  for (size_t i = 0; i < ms.size(); ++i)
    if (front[i]) f.push_back(&ms[i]);
  std::sort(f.begin(), f.end(), [](auto a, auto b) { return a->median_ms < b->median_ms; });
  svg << "<polyline fill='none' stroke='black' stroke-dasharray='4 3' points='";
  for (auto* m : f) svg << X(m->median_ms) << "," << Y(m->rmse) << " ";
  svg << "'/>\n";
  std::vector<double> labelled;  // the baseline appears in every series: label each error once
  for (size_t i = 0; i < ms.size(); ++i) {
    const auto& m = ms[i];
    if (!m.note.empty()) continue;
    const bool repeat = std::any_of(labelled.begin(), labelled.end(), [&](double e) { return std::abs(e - m.rmse) < 1e-7; });
    labelled.push_back(m.rmse);
    svg << "<circle cx='" << X(m.median_ms) << "' cy='" << Y(m.rmse) << "' r='" << (front[i] ? 6 : 4) << "' fill='"
        << colour.at(m.p.series) << "'" << (front[i] ? " stroke='black'" : "") << "><title>" << m.p.series << ": " << m.p.label
        << "</title></circle>\n";
    if (!repeat)
      svg << "<text x='" << X(m.median_ms) + 7 << "' y='" << Y(m.rmse) + 3 << "' font-size='9'>"
          << (std::abs(m.rmse - ms[2].rmse) < 1e-7 ? std::string("baseline") : m.p.label) << "</text>\n";
  }
  int row = 0;
  for (const auto& [series, c] : colour) {
    svg << "<circle cx='" << W - R + 20 << "' cy='" << T + 10 + 18 * row << "' r='5' fill='" << c << "'/><text x='" << W - R + 30
        << "' y='" << T + 14 + 18 * row << "'>" << series << "</text>\n";
    ++row;
  }
  svg << "<text x='" << W - R + 14 << "' y='" << T + 14 + 18 * row << "'>-- Pareto front (ringed)</text>\n</svg>\n";
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out = argc > 1 ? argv[1] : "docs";
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 7;
  auto renderer = render::Renderer::create({});
  if (!renderer) {
    std::cerr << renderer.error().format() << "\n";
    return 1;
  }
  std::vector<Point> points;
  for (const char* s : {"flat", "gouraud", "phong"}) points.push_back({"shading", s, s});
  for (int seg : {8, 16, 32, 64, 128}) points.push_back({"density", std::to_string(seg) + " segments", "phong", seg});
  for (int s : {0, 2, 4, 8}) points.push_back({"msaa", "MSAA " + std::to_string(s), "phong", 64, s});
  for (int k : {1, 2, 4}) points.push_back({"supersampling", "SSAA " + std::to_string(k) + "x", "phong", 64, 0, k});
  const auto& course = bench::canonical_course();
  for (auto [w, h] : {std::pair{course.width / 2, course.height / 2}, {course.width, course.height}, {2 * course.width, 2 * course.height}})
    points.push_back({"resolution", std::to_string(w) + "x" + std::to_string(h), "phong", 64, 4, 1, w, h});
  for (bool m : {true, false}) points.push_back({"precision", m ? "mediump" : "highp", "phong", 64, 4, 1, 0, 0, m});
  for (auto& p : points)
    if (p.width == 0) p.width = course.width, p.height = course.height;

  auto sphere_of_course = course::reference_sphere(course);
  if (!sphere_of_course) {
    std::cerr << sphere_of_course.error().format() << "\n";
    return 1;
  }
  const reference::PhongSphere scene = *sphere_of_course;
  std::map<std::pair<int, int>, image::Image> references;
  std::vector<Measured> results;
  for (const auto& p : points) {
    Measured m{p};
    auto& ref = references[{p.width, p.height}];
    if (ref.bytes.empty()) ref = reference::raycast(scene, p.width, p.height, 8);
    const scene::Mesh sphere = scene::uv_sphere(scene.radius, scene.center, p.segments);
    m.triangles = sphere.triangle_count();
    const auto request = request_for(p);
    image::Image frame;
    const auto run = [&]() -> Expected<double> {
      const auto start = Clock::now();
      auto report = renderer->render(request, sphere, [&](int, const image::Image& f, bool) { frame = f; });
      if (!report) return report.take_error();
      m.samples = report->samples;
      return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    };
    if (auto warm = run(); !warm) {
      m.note = warm.error().message;
      results.push_back(m);
      std::cerr << p.series << " " << p.label << ": " << m.note << "\n";
      continue;
    }
    // Supersampling's cost includes the box filter back down to the output size.
    std::vector<double> times;
    std::vector<double> gl;
    for (int i = 0; i < repeats; ++i) {
      double t = *run();
      const auto t0 = Clock::now();
      gl = downsample(frame, p.supersample);
      if (p.supersample > 1) t += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      times.push_back(t);
    }
    std::sort(times.begin(), times.end());
    m.median_ms = times[times.size() / 2];
    m.min_ms = times.front();
    m.max_ms = times.back();
    errors(gl, ref, m.rmse, m.max_error);
    std::cerr << p.series << " " << p.label << ": " << fmt(m.median_ms) << " ms, RMSE " << m.rmse << "\n";
    results.push_back(m);
  }

  std::vector<bool> front(results.size(), false);
  for (size_t i = 0; i < results.size(); ++i) {
    if (!results[i].note.empty()) continue;
    front[i] = true;
    for (size_t j = 0; j < results.size(); ++j)
      if (j != i && results[j].note.empty() && results[j].median_ms <= results[i].median_ms && results[j].rmse <= results[i].rmse &&
          (results[j].median_ms < results[i].median_ms || results[j].rmse < results[i].rmse))
        front[i] = false;
  }

  std::ofstream csv(out + "/accuracy.csv");
  csv << "series,setting,shading,segments,triangles,msaa,samples,supersample,width,height,precision,median_ms,min_ms,max_ms,rmse,max_error,pareto,note\n";
  std::ostringstream table;
  table << "| series | setting | ms per frame (median, min-max) | RMSE | max error | Pareto |\n| --- | --- | --- | --- | --- | --- |\n";
  for (size_t i = 0; i < results.size(); ++i) {
    const auto& m = results[i];
    csv << m.p.series << "," << m.p.label << "," << m.p.shading << "," << m.p.segments << "," << m.triangles << "," << m.p.msaa << "," << m.samples << ","
        << m.p.supersample << "," << m.p.width << "," << m.p.height << "," << (m.p.mediump ? "mediump" : "highp") << ","
        << m.median_ms << "," << m.min_ms << "," << m.max_ms << "," << m.rmse << "," << m.max_error << "," << front[i] << ",\""
        << m.note << "\"\n";
    const std::string label = m.p.label + (m.note.empty() && m.p.msaa > 0 && m.samples != m.p.msaa ? " (driver gave " + std::to_string(m.samples) + ")" : "");
    table << "| " << m.p.series << " | " << label << " | "
          << (m.note.empty() ? fmt(m.median_ms) + " (" + fmt(m.min_ms) + "-" + fmt(m.max_ms) + ")" : "not available: " + m.note) << " | "
          << (m.note.empty() ? fmt(m.rmse * 1000, 2) + "e-3" : "-") << " | " << (m.note.empty() ? fmt(m.max_error, 3) : "-") << " | "
          << (front[i] ? "yes" : "") << " |\n";
  }
  std::ofstream(out + "/accuracy_table.md") << table.str();
  write_svg(results, front, out + "/accuracy.svg");
  std::cout << table.str();
  return 0;
}
