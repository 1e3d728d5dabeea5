#include "grade/camera_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "core/words.h"

namespace shadelab::grade {

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", std::abs(v) < 5e-7 ? 0.0 : v);
  return buf;
}


std::string times(double ratio) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", ratio);
  return buf;
}

std::string place(const glm::dvec3& p) { return "(" + number(p.x) + ", " + number(p.y) + ", " + number(p.z) + ")"; }

}  // namespace

std::string words(const CameraView& v) { return number(v.lens_mm) + " mm lens at " + place(v.location); }

std::vector<CameraView> views_to_try(const std::vector<CameraView>& handout) {
  std::vector<CameraView> out = handout;  // the handout's own first
  for (const auto& at : handout)
    for (const auto& lens : handout) {
      const CameraView v{lens.lens_mm, at.location};
      if (std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
    }
  return out;
}

CameraVerdict judge_camera(const Outline& outline, const CameraView& handout, const std::vector<ViewOutline>& views,
                           const CameraCheckOptions& options) {
  CameraVerdict v;
  const ViewOutline* own = nullptr;
  const ViewOutline* best = nullptr;
  double best_overlap = -1, runner_up = -1;
  Outline mine;  // the student's on the views' grid, resampled once (judge_cameras renders a set's views at one size)
  for (const auto& view : views) {
    if (mine.width != view.outline.width || mine.height != view.outline.height) mine = resampled(outline, view.outline.width, view.outline.height);
    const double o = overlap(mine, view.outline);
    if (view.view == handout) own = &view, v.overlap = o;
    if (o > best_overlap) runner_up = best_overlap, best_overlap = o, best = &view;
    else runner_up = std::max(runner_up, o);
  }
  if (!own) return {false, "not checked: no render of the handout's camera to compare with", {}, 0, 0};
  if (mine.width != own->outline.width || mine.height != own->outline.height) mine = resampled(outline, own->outline.width, own->outline.height);
  const double coverage = mine.coverage(), expected = own->outline.coverage();
  v.size_ratio = expected > 0 ? std::sqrt(coverage / expected) : 0;
  if (coverage == 0 || coverage > 0.95) {
    v.message = "not checked: the subject cannot be told from the background (" + percent(coverage) + " of the image differs from its border's colour)";
    return v;
  }
  const bool clear = best_overlap >= options.matches && best_overlap - runner_up >= options.stands_out;
  const bool own_matches = v.overlap >= options.matches && v.overlap >= best_overlap - options.stands_out;
  if (own_matches) {
    v.pass = true;
    v.seen = handout;
    v.message = "matches the handout's camera (a " + words(handout) + "; the outlines overlap by " + percent(v.overlap) + ")";
    if (!clear && best->view != handout) v.message += "; a " + words(best->view) + " gives about the same outline";
    return v;
  }
  if (clear) {
    v.seen = best->view;
    v.message = "shows a " + words(best->view) + " (the outlines overlap by " + percent(best_overlap) + "), not the handout's " + words(handout);
    if (best->view.location == handout.location) v.message += ": the camera is in place, the lens is not";
    else if (best->view.lens_mm == handout.lens_mm) v.message += ": the lens is right, the camera is not where the handout puts it";
    return v;
  }
  const OutlinePlace at = place_of(mine), want = place_of(own->outline);
  v.message = "does not match the handout's camera, and no other of its cameras stands out (the outlines overlap by " + percent(v.overlap) +
              "): the subject is " + times(v.size_ratio) + " times the size the handout's camera gives, its centre at (" +
              times(at.centre_x) + ", " + times(at.centre_y) + ") of the frame where the handout's is at (" + times(want.centre_x) + ", " +
              times(want.centre_y) + ")";
  return v;
}

Expected<std::vector<CameraVerdict>> judge_cameras(const std::vector<HandedInCamera>& set, const RenderView& render,
                                                   const CameraCheckOptions& options) {
  std::vector<CameraView> handout;
  for (const auto& c : set) handout.push_back(c.handout);
  const std::vector<CameraView> tried = views_to_try(handout);
  std::map<std::pair<int, int>, std::vector<ViewOutline>> views;  // by grid size: one set per aspect
  std::vector<CameraVerdict> out;
  for (size_t i = 0; i < set.size(); ++i) {
    const HandedInCamera& c = set[i];
    if (!c.image) {
      out.push_back({false, c.problem, {}, 0, 0});
      continue;
    }
    const int width = std::min(options.grid_width, c.image->width);
    const int height = std::max(1, static_cast<int>(std::lround(static_cast<double>(width) * c.image->height / c.image->width)));
    auto& at_size = views[{width, height}];
    if (at_size.empty())
      for (const auto& view : tried) {
        auto outline = render(view, width, height);
        if (!outline) return outline.take_error();
        at_size.push_back({view, std::move(*outline)});
      }
    CameraVerdict v = judge_camera(outline_of(*c.image, options.background_tolerance), c.handout, at_size, options);
    for (size_t j = 0; j < i; ++j)
      if (set[j].image && set[j].image->width == c.image->width && set[j].image->height == c.image->height &&
          set[j].image->bytes == c.image->bytes) {
        v.pass = false;
        v.message = "the same image as " + set[j].file + ": " + v.message;
        break;
      }
    out.push_back(std::move(v));
  }
  return out;
}

}  // namespace shadelab::grade
