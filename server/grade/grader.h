#pragma once
// From rendered frames to a verdict, a score and messages a student understands. Pure CPU work
// on images: the worker renders, this decides.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "image/metrics.h"

namespace shadelab::grade {

// Whether an 8-bit RGBA pixel is the page's clear colour, opaque black: the object is every pixel
// that is not (a shader that draws opaque black draws nothing the grader can tell from it).
inline bool is_clear(const std::uint8_t* rgba) { return rgba[0] == 0 && rgba[1] == 0 && rgba[2] == 0 && rgba[3] == 255; }

// Every threshold of a verdict. A course profile's `tolerance` sets its own (Course::tolerance);
// these are the defaults where it says nothing.
struct GradeOptions {
  image::CompareOptions compare;        // per-channel threshold 0.016 (~4/255), spatial tolerance off
  double max_failing_fraction = 0.01;   // a frame fails past 1% failing object pixels (Blender's tests: 1%)
  double max_score = 1.0;
  // Saved frames (another rasteriser's): closer_than_reference below, for them.
  double saved_frames_closer_than_reference = 0.25;
  // Saved frames whose outline overlaps the one rendered by less than this (at the worst frame)
  // show another shape (another mesh, another camera), whatever the shading.
  double same_outline = 0.9;
  // A known mistake explains frames when every frame matches its render. Frames from another
  // rasteriser (a student's saved frames) may not match a mistake whose pixels are each a
  // triangle's own colour (flat shading on a mesh of pixel-sized triangles), so for them a mistake
  // also explains frames its render is this much closer to than the reference is (in mean failing
  // pixels); 0 keeps the strict rule. Grader-side only: not on the wire.
  double closer_than_reference = 0;
};

struct FrameGrade {
  image::FrameMetrics metrics;
  // Failing pixels as a share of the object's pixels (where either image is not the clear
  // colour): the mesh covers a tenth of a homework frame, and a share of the whole frame would
  // let a tenth of the object be wrong before a frame failed. The verdict uses this one.
  double failing_fraction_of_object = 0;
  image::NonFinite non_finite;
  bool pass = false;
};

// Frames shared between a worker's reference cache and the grades that read them: a class graded
// against one checkpoint holds its reference renders once, not once more per submission.
using SharedFrames = std::vector<std::shared_ptr<const image::Image>>;

// A known mistake, rendered: the same frames as the student's.
struct RenderedMistake {
  std::string id, message;
  SharedFrames frames;
};

struct GradeResult {
  bool pass = false;
  double score = 0, max_score = 1;
  std::vector<FrameGrade> frames;
  std::vector<std::string> messages;
  std::string diagnosis;  // id of the mistake recognised, "swapped_channels", "nan", or ""
};

// `student` and `reference` are RGBA8 frames; `student_non_finite` counts NaN and infinity in the
// same frames as the program computed them (the census its rewritten fragment shader draws beside
// its colours, shader/uniform_variants.h: the 8-bit canvas hides them), one per frame; empty to
// skip that check.
GradeResult grade(const SharedFrames& student, const std::vector<image::NonFinite>& student_non_finite,
                  const SharedFrames& reference, const std::vector<RenderedMistake>& mistakes, const GradeOptions& options);

// grade() in two steps, for a caller that finds the known mistakes only for a submission that
// fails (they cost renders or reads): `assess` compares with the reference alone and, for a
// pass, says so; `explain` adds to a failing result which mistake explains it and how far off it
// is. grade() is assess, then explain when it failed.
GradeResult assess(const SharedFrames& student, const std::vector<image::NonFinite>& student_non_finite, const SharedFrames& reference,
                   const GradeOptions& options);
// `recognised`: a known mistake found without frames of its own (by the formula's reading,
// grade/formula_explanation.h), the diagnosis before any rendered one; it has no frames.
void explain(GradeResult& result, const SharedFrames& student, const SharedFrames& reference, const std::vector<RenderedMistake>& mistakes,
             const GradeOptions& options, const RenderedMistake* recognised = nullptr);

}  // namespace shadelab::grade
