#pragma once
// The subject of a render made in another program (a student's Blender render): the pixels that
// are not its background. The background is the colour most of the image's border has, whatever
// it is (the world's grey, a colour the student chose, a transparent film), and it is what the
// border reaches through pixels of about that colour; the rest, holes included, is the subject. So
// the engine, the lights and the subject's own shading do not move the outline, unless a side of
// the subject turns the background's very colour where it meets it.
#include <cstdint>
#include <vector>

#include "image/image.h"

namespace shadelab::grade {

struct Outline {
  int width = 0, height = 0;
  std::vector<std::uint8_t> inside;  // 1 where the subject is, rows top-down

  double coverage() const;  // share of the image inside
  bool touches_border() const;
};

// An 8-bit RGBA image's outline; `tolerance` is how far (per channel, 0..1) a pixel may be from
// the background's colour and still be background.
Outline outline_of(const image::Image& rgba8, double tolerance = 0.06);

// The outline on a width x height grid over the same frame: a cell is inside when most of the area
// it covers is.
Outline resampled(const Outline& outline, int width, int height);

// Intersection over union of two outlines of one size: 1 for the same outline, 0 for disjoint.
double overlap(const Outline& a, const Outline& b);

// Where the subject is and how large: its centre and its box, in fractions of the frame's width
// and height (0..1, from the top left).
struct OutlinePlace {
  double centre_x = 0, centre_y = 0;
  double left = 0, top = 0, right = 0, bottom = 0;
};
OutlinePlace place_of(const Outline& outline);  // all 0 for an empty outline

}  // namespace shadelab::grade
