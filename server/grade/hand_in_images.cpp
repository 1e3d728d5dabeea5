#include "grade/hand_in_images.h"

#include "grade/camera_check.h"
#include "grade/render_check.h"
#include "image/png_decode.h"

namespace shadelab::grade {

namespace {

// The dolly zoom's set: its subject (the first image's scene) rendered from each view asked.
Expected<std::vector<CameraVerdict>> judge_camera_set(const std::vector<HandedInCamera>& cameras, const scene::SceneDescription& subject,
                                                      const RenderScene& render) {
  const CameraCheckOptions options;
  const auto render_view = [&](const CameraView& view, int width, int height) -> Expected<Outline> {
    scene::SceneDescription s = subject;
    s.camera.lens_mm = view.lens_mm;
    s.camera.location = view.location;
    s.render.width = width, s.render.height = height, s.render.percentage = 100;
    s.render.engine = scene::Engine::workbench;  // the outline is all that is compared: the cheapest engine
    auto rendered = render(s);
    if (!rendered) return rendered.take_error();
    return outline_of(*rendered, options.background_tolerance);
  };
  return judge_cameras(cameras, render_view, options);
}

}  // namespace

Expected<std::vector<ImageVerdict>> judge_hand_in_images(std::vector<HandInImage> images, unsigned max_side, const RenderScene& render) {
  std::vector<ImageVerdict> out(images.size());
  std::vector<HandedInCamera> cameras;
  std::vector<size_t> camera_at;
  const scene::SceneDescription* subject = nullptr;
  for (size_t i = 0; i < images.size(); ++i) {
    HandInImage& image = images[i];
    std::optional<image::Image> decoded;
    std::string problem = image.problem;
    if (problem.empty()) {
      auto d = image::decode_png(image.png, max_side);
      if (d) decoded = std::move(*d);
      else problem = image.file + " cannot be read: " + d.error().message;
    }
    if (image.scene) {
      if (!subject) subject = &*image.scene;
      cameras.push_back({image.file, {image.scene->camera.lens_mm, image.scene->camera.location}, std::move(decoded), problem});
      camera_at.push_back(i);
    } else if (!decoded) {
      out[i] = {false, problem, ""};
    } else {
      const RenderCheck r = check_render(*decoded);
      out[i] = {r.pass, r.facts_line(), render_check_leaves_out(image.objects)};
    }
  }
  if (cameras.empty()) return out;
  auto verdicts = judge_camera_set(cameras, *subject, render);
  if (!verdicts) return verdicts.take_error();
  for (size_t k = 0; k < cameras.size(); ++k) {
    const CameraVerdict& v = (*verdicts)[k];
    out[camera_at[k]] = {v.pass, v.message, cameras[k].image.has_value() ? kCameraCheckLeavesOut : ""};
  }
  return out;
}

}  // namespace shadelab::grade
