#pragma once
// Shared by the tests: one real EGL renderer per test binary (llvmpipe where there is no GPU),
// rendering helpers and PNG decoding through OpenImageIO.
#include <string>
#include <vector>

#include "course/course.h"
#include "grade/grade_spec.h"
#include "image/image.h"
#include "render/renderer.h"

namespace shadelab::testkit {

render::Renderer& shared_renderer();

struct Rendered {
  std::vector<image::Image> frames;
  std::vector<bool> opaque;
  render::RenderReport report;
};
// Renders `request` on `mesh`; fails the test (and returns no frames) on an error.
Expected<Rendered> render_frames(const render::RenderRequest& request, const scene::Mesh& mesh);

// The built-in course (courses/cs148-summer2022.json): its job, presets and meshes.
const course::Course& course();
// The course's job for one of its presets: its canvas, frames, samples and page setup.
render::RenderRequest preset_request(const std::string& preset);
// One of the course's meshes, parsed once per test binary.
const scene::Mesh& builtin(const std::string& name);

// What a student's page saves: `preset` drawn on the course's default mesh at each frame's
// nominal angle minus its lag (degrees), as PNGs named as the page names them under `prefix`.
std::vector<grade::SavedFrame> saved_frames(const std::string& preset, const std::string& prefix, const std::vector<double>& lags);

// Where a 60 Hz page draws the course's 9 frames (each after the first 0.05-0.3 degrees behind its
// nominal angle), for `shadelab render --angles`: frames as a student's page saves them, where
// ShadeLab's own at the exact angles are no hand-in (grade/provenance.h).
inline constexpr const char* kPageAngles = "0,19.88,39.79,59.95,79.7,99.83,119.74,139.91,159.77";

// A request whose vertex shader covers the viewport with one triangle and whose fragment shader
// is `fragment_body` inside main() writing `out vec4 c`.
render::RenderRequest fullscreen_request(const std::string& fragment_body, const std::string& declarations = "");

// PNG/EXR bytes -> RGBA image, alpha as stored (no premultiplication on read).
image::Image decode(const std::vector<std::uint8_t>& bytes);
std::array<int, 4> pixel(const image::Image& img, int x, int y);

}  // namespace shadelab::testkit
