#pragma once
// Saved frames drawn with a flat colour, placed by their triangles' edges. The outlines fit a saved
// frame's angle to about a hundredth of a degree (grade/lag_fit.h's fit_outline_lags); a flat
// colour changes at every edge of the mesh, and 0.012 degrees moves the edges by enough to leave
// 1.1% of a frame off, more than the rule allows, though the reading is right. The edges
// themselves tell the angle more closely: the flat colour's squared error grows with the distance
// they move from where the student's frame has them (each sample an edge crosses is one step of
// it), a V in the angle's offset with its point at the frame's own angle. Read at the fitted angle
// and `kEdgeReach` either side (one render of the flat colour), the V's point is where its sides
// meet; a second render there is the geometry the formula reads the frames on. Only the frames
// the outlines' angles leave near or past the rule are placed: the renders are of them alone.
#include <functional>
#include <optional>
#include <vector>

#include "core/expected.h"
#include "grade/grader.h"
#include "model/fit.h"

namespace shadelab::grade {

// Degrees either side of a frame's fitted angle the edges are read at: past what the outline fit
// misses by (~0.01), and short of where edges cross samples too often for the error to grow in
// step with the distance (0.012 degrees moves the bunny's edges by 0.04 of a pixel at 512 x 512).
inline constexpr double kEdgeReach = 0.012;

// The geometry's flat colour (model::Quantity::flat_colour) rendered at angle `angle[i]` of the
// frames moved by `offset[i]` degrees, for each i: one render, a frame each.
using MovedFlatColour = std::function<Expected<SharedFrames>(const std::vector<std::size_t>& angle, const std::vector<double>& offset)>;

struct EdgePlacement {
  std::vector<double> offsets;                // each angle's, in degrees (0 where it was not placed)
  std::vector<model::FrameSurface> surfaces;  // the geometry with the flat colour there, one per angle
};

// The angles of `frames` (light after light, `angles` frames a light, each on its angle's surface)
// at which `fit` draws some frame off on more than half the share it allows, placed by the edges
// of what it draws; none where there is none or a render fails.
std::optional<EdgePlacement> placed_by_edges(const model::Fit& fit, const std::vector<model::DrawnFrame>& frames, std::size_t angles,
                                             const model::FitOptions& options, const MovedFlatColour& moved);

// Where a V through (-reach, below), (0, at) and (reach, above) has its point, within [-reach,
// reach]: the steeper side's slope is the V's, and the sides' difference is twice its point's
// distance from 0 at that slope. With no V (the middle highest), the lower side.
double v_point(double below, double at, double above, double reach);

}  // namespace shadelab::grade
