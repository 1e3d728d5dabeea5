#pragma once
// Where a submission's frames differ from the reference's, in the parts of the object the
// homework names: the highlight, the lit side, the unlit side and the outline (each pixel's part
// from the formula at the course's values; for the normal's colour, the way the normal faces),
// and how: brighter, darker or another hue, with the mean difference of each channel. What the
// grader says when no change to the formula explains the frames.
#include <string>
#include <vector>

#include "grade/grader.h"
#include "model/fit.h"

namespace shadelab::grade {

struct RegionDifference {
  std::string region;       // "the highlight"
  double share = 0;         // of its pixels, off by more than the threshold
  double mean[3] = {0, 0, 0};  // student - reference on those pixels, per channel, in [-1, 1]
};

// Under the page's light (`light`), frame by frame: `student[k]` and `reference[k]` on `surfaces[k]`.
// Regions with no pixel off are left out.
std::vector<RegionDifference> difference_regions(const std::vector<model::FrameSurface>& surfaces, const SharedFrames& student,
                                                 const SharedFrames& reference, const model::Light& light, const model::FitOptions& course);

// "the highlight: 62% of its pixels, darker (red -0.05, green -0.20, blue -0.40)"
std::string to_words(const RegionDifference& difference);

}  // namespace shadelab::grade
