#pragma once
// A render the handout describes only in words ("two objects on a plane, both fully within the
// image, with different material properties": the Eevee render) checked for what the image alone
// shows without guessing: it is a PNG, of some size, and it is not blank. Whether it shows the
// objects, each within the frame, with materials that differ, stays the TA's: a metal object
// mirrors the floor at its edge and a subsurface one softens its own, so telling objects from the
// floor in a picture would be a guess (measured in docs/grading.md, "The Eevee render").
#include <string>
#include <vector>

#include "image/image.h"

namespace shadelab::grade {

struct RenderFact {
  std::string name;  // "a PNG", "not blank"
  bool holds = false;
  std::string detail;  // the numbers behind it
};

struct RenderCheck {
  bool pass = false;  // every fact holds
  std::vector<RenderFact> facts;
  std::string facts_line() const;  // "a PNG: yes (W x H); not blank: yes (61.5% of ...)"
};

struct RenderCheckOptions {
  double blank = 0.01;  // under this share of pixels off the commonest colour, the image is blank
};

RenderCheck check_render(const image::Image& rgba8, const RenderCheckOptions& options = {});

// What stays the TA's, for a render the handout asks `objects` objects of.
std::string render_check_leaves_out(int objects);

}  // namespace shadelab::grade
