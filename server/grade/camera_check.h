#pragma once
// A render handed in for one of the handout's cameras (the dolly zoom's camera_25.png, _50, _100)
// checked by the subject's outline (grade/outline.h): its size, its place in the frame and its
// shape, which is the perspective a lens at a distance gives. ShadeLab renders the subject from
// every camera the handout names and every lens at every place among them, at the image's aspect;
// the image shows the camera whose outline it overlaps, when one stands out. What the outline does
// not show (the engine, the lights, the materials, the background) is not checked, and each
// verdict says so.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/expected.h"
#include "grade/outline.h"
#include "image/image.h"

namespace shadelab::grade {

struct CameraView {
  double lens_mm = 0;
  glm::dvec3 location{0.0};
  bool operator==(const CameraView&) const = default;
};
std::string words(const CameraView& view);  // "25 mm lens at (0, -4, 0)"

// Every lens of `handout` at every place of it: the views a render may show.
std::vector<CameraView> views_to_try(const std::vector<CameraView>& handout);

struct ViewOutline {
  CameraView view;
  Outline outline;  // ShadeLab's render of the subject from the view
};

struct CameraVerdict {
  bool pass = false;
  std::string message;             // what the TA reads: "matches the handout's camera (a 25 mm lens at (0, -4, 0))"
  std::optional<CameraView> seen;  // the view it shows, when one stands out
  double overlap = 0;              // with the handout's view, 0..1
  double size_ratio = 0;           // the subject's size against the handout's view (linear)
};

// Thresholds, measured (docs/grading.md, "The Blender half's cameras").
struct CameraCheckOptions {
  // Blender dithers what it writes by up to 1/255, so the background is about 2.5/255 wide.
  double background_tolerance = 0.01;
  double matches = 0.9;      // an outline overlapping a view by this much shows it ...
  double stands_out = 0.01;  // ... when no other view overlaps within this of it
  int grid_width = 320;      // the views are rendered this wide (at most), at the image's aspect
};

// `outline`: the student's, any size; `views`: views_to_try's renders, each at the image's aspect.
CameraVerdict judge_camera(const Outline& outline, const CameraView& handout, const std::vector<ViewOutline>& views,
                           const CameraCheckOptions& options = {});

// The set a student hands in: each render with the camera the handout asks for it.
struct HandedInCamera {
  std::string file;                   // images/camera_25.png
  CameraView handout;
  std::optional<image::Image> image;  // RGBA8; nullopt: `problem` says why
  std::string problem;                // "not in the submission", "not a PNG file"
};

// ShadeLab's render of the subject from a view, width x height, as an outline.
using RenderView = std::function<Expected<Outline>(const CameraView& view, int width, int height)>;

// Each render judged (judge_camera), and one image handed in for two cameras named as such. An
// error is only the renderer's: what the student handed in is its verdict.
Expected<std::vector<CameraVerdict>> judge_cameras(const std::vector<HandedInCamera>& set, const RenderView& render,
                                                   const CameraCheckOptions& options = {});

// What no verdict checks, in the TA's words.
inline constexpr const char* kCameraCheckLeavesOut =
    "The outline shows the camera and the lens; the engine, lights, materials and background are the TA's to look at.";

}  // namespace shadelab::grade
