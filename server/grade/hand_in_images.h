#pragma once
// The Blender half's images a student handed in, each judged as the course asks: against a scene
// (the dolly zoom's cameras, grade/camera_check.h: the first such image's subject is the set's),
// or for the objects in it (grade/render_check.h). A worker decodes the stranger's PNGs here and
// draws the views asked of it; what is judged, and how, is decided in this file, not the worker.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/expected.h"
#include "grade/image_check.h"
#include "image/image.h"
#include "scene/scene_description.h"

namespace shadelab::grade {

struct HandInImage {
  std::string file;                              // images/camera_25.png
  std::optional<scene::SceneDescription> scene;  // the course's, validated when the profile was read
  int objects = 0;                               // without a scene: how many objects it must show
  std::string png;                               // empty: `problem` says why
  std::string problem;                           // "not in the submission"
};

// ShadeLab's render of `scene` as it stands (its camera, size and engine set by the caller), RGBA8.
using RenderScene = std::function<Expected<image::Image>(const scene::SceneDescription& scene)>;

// One verdict per image, in order; PNGs larger than `max_side` on a side are not decoded. An Error
// is only the renderer's: what the student handed in is its verdict.
Expected<std::vector<ImageVerdict>> judge_hand_in_images(std::vector<HandInImage> images, unsigned max_side, const RenderScene& render);

}  // namespace shadelab::grade
