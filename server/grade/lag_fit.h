#pragma once
// Which rotation each frame a student saved from their browser was drawn at. The page draws with
// the previous animation frame's time, so frame k (k >= 1) is at 20k degrees minus up to one frame
// interval of its clock: 0 to 0.33 degrees at 60 Hz, more on a slow machine (docs/grading.md).
// Frame 0 is drawn at exactly 0. A deterministic render at exactly 20k differs from a correct
// student's frame by 1-2% of its pixels; at the right lag, by ~0.1%.
//
// So the reference is rendered at a grid of angles: each frame's nominal angle and more behind it,
// `step` degrees apart (0.1 degrees over a 0.7-degree window: 8 angles a frame, 65 for the job).
// Each saved frame is compared with its own frame's angles, the best refined by a parabola through
// its neighbours (0.1 degrees turns the bunny's outline by a third of a pixel at 512 x 512, where
// the difference still grows with the square of the angle), and with every other frame's nominal
// angle: a frame that fits another frame better was saved out of order, or twice.
#include <optional>
#include <vector>

#include "grade/grader.h"
#include "image/image.h"

namespace shadelab::grade {

struct LagGrid {
  int frames = 9;
  double degrees_per_frame = 20;
  // Degrees behind the nominal angle searched: one frame interval of a 30 Hz clock (0.67 degrees),
  // a slow machine's page, not only a 60 Hz one's (0.33).
  double window = 0.7;
  double step = 0.1;

  int steps() const;  // angles a frame k >= 1 is searched at (8)
  // The grid's angles: frame 0's, then each later frame's, nominal first, lag growing.
  std::vector<double> angles() const;
  // The index in angles() of frame k at lag step j (j = 0 for frame 0).
  size_t index(int frame, int step) const;
  double nominal(int frame) const { return frame * degrees_per_frame; }
};

struct LagFit {
  int frame = 0;
  size_t best = 0;            // index in the grid of the closest render
  double lag_degrees = 0;     // nominal minus the fitted angle, refined between grid steps
  bool beyond_window = false; // the best fit is the window's far edge, and the fit does not turn before it: the frame may lag more
  std::optional<int> looks_like;  // another frame's nominal angle fits it better
  double residual = 0;        // squared_difference at the best grid angle
};

// The fits' residuals summed: how well a set of renders explains the saved frames at all.
double total_residual(const std::vector<LagFit>& fits);

// One fit per saved frame; `grid_frames` is the reference rendered at grid.angles().
std::vector<LagFit> fit_lags(const std::vector<const image::Image*>& saved, const SharedFrames& grid_frames, const LagGrid& grid);

// The same fit by the outline alone (the pixels drawn over the clear colour), whatever the shading:
// frames shaded otherwise than the reference fit its grid by their shading, at the wrong angles,
// but their outline is the reference's. Each fit's residual counts pixels, and looks_like is not set.
std::vector<LagFit> fit_outline_lags(const std::vector<const image::Image*>& saved, const SharedFrames& grid_frames, const LagGrid& grid);

// The sum of squared RGB differences of two frames of one size, in [0, 3 * pixels].
double squared_difference(const image::Image& a, const image::Image& b);

}  // namespace shadelab::grade
