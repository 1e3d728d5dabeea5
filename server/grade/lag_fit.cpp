#include "grade/lag_fit.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace shadelab::grade {

int LagGrid::steps() const { return static_cast<int>(std::floor(window / step + 1e-9)) + 1; }

std::vector<double> LagGrid::angles() const {
  std::vector<double> out = {nominal(0)};
  for (int k = 1; k < frames; ++k)
    for (int j = 0; j < steps(); ++j) out.push_back(nominal(k) - j * step);
  return out;
}

size_t LagGrid::index(int frame, int j) const {
  return frame == 0 ? 0 : 1 + static_cast<size_t>(frame - 1) * static_cast<size_t>(steps()) + static_cast<size_t>(j);
}

double squared_difference(const image::Image& a, const image::Image& b) {
  SHADELAB_CHECK(a.bytes.size() == b.bytes.size() && a.type == image::PixelType::u8, "frames of one size and type");
  double sum = 0;
  for (size_t i = 0; i < a.bytes.size(); i += 4)
    for (size_t c = 0; c < 3; ++c) {
      const double d = (static_cast<double>(a.bytes[i + c]) - b.bytes[i + c]) / 255.0;
      sum += d * d;
    }
  return sum;
}

namespace {

// The vertex of the parabola through (-1, left), (0, mid), (1, right), in steps from the middle;
// 0 when the three do not bend upwards.
double parabola_vertex(double left, double mid, double right) {
  const double curvature = left - 2 * mid + right;
  if (curvature <= 0) return 0;
  return std::clamp(0.5 * (left - right) / curvature, -1.0, 1.0);
}

// The best step refined between its neighbours: the parabola through the three steps around it
// (the first three or the last three at the window's edges: a lag of 0.05 degrees is best at step
// 0 and lies between it and step 1), kept within half a step of the best and inside the window.
// Three that do not bend upwards say nothing of where between the steps the best lies: the best
// step itself (at the window's edge, not the middle three's centre: outlines drawn at exactly the
// nominal angle differ from the grid's next steps by a count that grows more slowly than linearly,
// and were fitted half a step late, where a flat colour's every edge has moved).
double refined_step(const std::vector<double>& error, int best) {
  const int last = static_cast<int>(error.size()) - 1;
  if (last < 2) return best;
  const int c = std::clamp(best, 1, last - 1);
  const auto e = [&](int j) { return error[static_cast<size_t>(j)]; };
  if (e(c - 1) - 2 * e(c) + e(c + 1) <= 0) return best;
  const double vertex = c + parabola_vertex(e(c - 1), e(c), e(c + 1));
  return std::clamp(vertex, std::max(0.0, best - 0.5), std::min<double>(last, best + 0.5));
}

// Whether the differences at the window's last three steps turn upward before its edge: the frame
// was drawn inside the window, a little short of the edge (a 30 Hz clock's 0.67 degrees in a
// 0.7-degree window), not beyond it.
bool turns_before_edge(const std::vector<double>& error) {
  const size_t n = error.size();
  if (n < 3) return false;
  const double left = error[n - 3], mid = error[n - 2], right = error[n - 1];
  const double curvature = left - 2 * mid + right;
  return curvature > 0 && 0.5 * (left - right) / curvature < 1.0;
}

// The pixels one frame draws over the clear colour and the other does not.
double outline_difference(const image::Image& a, const image::Image& b) {
  SHADELAB_CHECK(a.bytes.size() == b.bytes.size() && a.type == image::PixelType::u8, "frames of one size and type");
  double count = 0;
  for (size_t i = 0; i < a.bytes.size(); i += 4) count += is_clear(&a.bytes[i]) != is_clear(&b.bytes[i]);
  return count;
}

using Difference = double (*)(const image::Image&, const image::Image&);

LagFit fit_one(int k, const image::Image& frame, const SharedFrames& grid_frames, const LagGrid& grid, Difference difference) {
  LagFit fit{k, grid.index(k, 0), 0, false, std::nullopt, 0};
  if (k == 0) {
    fit.residual = difference(frame, *grid_frames[fit.best]);
    return fit;
  }
  std::vector<double> error(static_cast<size_t>(grid.steps()));
  for (int j = 0; j < grid.steps(); ++j) error[static_cast<size_t>(j)] = difference(frame, *grid_frames[grid.index(k, j)]);
  const int best = static_cast<int>(std::min_element(error.begin(), error.end()) - error.begin());
  fit.best = grid.index(k, best);
  fit.lag_degrees = refined_step(error, best) * grid.step;
  fit.beyond_window = best + 1 == grid.steps() && !turns_before_edge(error);
  fit.residual = error[static_cast<size_t>(best)];
  return fit;
}

}  // namespace

std::vector<LagFit> fit_lags(const std::vector<const image::Image*>& saved, const SharedFrames& grid_frames, const LagGrid& grid) {
  SHADELAB_CHECK(grid_frames.size() == grid.angles().size(), "the reference grid must be rendered at the grid's angles");
  std::vector<LagFit> fits;
  for (int k = 0; k < static_cast<int>(saved.size()); ++k) {
    LagFit fit = fit_one(k, *saved[static_cast<size_t>(k)], grid_frames, grid, squared_difference);
    // Out of order, or saved twice: another frame's nominal angle fits clearly better.
    const double own = fit.residual;
    for (int m = 0; m < grid.frames; ++m) {
      if (m == k) continue;
      const double other = squared_difference(*saved[static_cast<size_t>(k)], *grid_frames[grid.index(m, 0)]);
      if (other < 0.5 * own && (!fit.looks_like || other < squared_difference(*saved[static_cast<size_t>(k)], *grid_frames[grid.index(*fit.looks_like, 0)])))
        fit.looks_like = m;
    }
    fits.push_back(fit);
  }
  return fits;
}

std::vector<LagFit> fit_outline_lags(const std::vector<const image::Image*>& saved, const SharedFrames& grid_frames, const LagGrid& grid) {
  SHADELAB_CHECK(grid_frames.size() == grid.angles().size(), "the reference grid must be rendered at the grid's angles");
  std::vector<LagFit> fits;
  for (int k = 0; k < static_cast<int>(saved.size()); ++k) fits.push_back(fit_one(k, *saved[static_cast<size_t>(k)], grid_frames, grid, outline_difference));
  return fits;
}

double total_residual(const std::vector<LagFit>& fits) {
  double sum = 0;
  for (const auto& f : fits) sum += f.residual;
  return sum;
}

}  // namespace shadelab::grade
