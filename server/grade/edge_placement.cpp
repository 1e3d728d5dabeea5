#include "grade/edge_placement.h"

#include <algorithm>

namespace shadelab::grade {

namespace {

// A frame is placed where the outlines' angle leaves more than half what it allows off: one just
// within the rule there (0.95% of 1.06%, 0.012 degrees from the page's angle) is placed too, so
// that the reading holds with room, and its lag is told to a few thousandths of a degree.
constexpr double kPlaced = 0.5;

// Angle k's surface with the flat colour read from `render`.
model::FrameSurface with_flat_colour(const model::FrameSurface& surface, const image::Image& render) {
  model::FrameSurface out = surface;
  model::add_quantity(out, render, model::Quantity::flat_colour);
  return out;
}

// What `fit` draws off at angle k, every light's frame of it on `surface`.
double error_at(const model::Fit& fit, const std::vector<model::DrawnFrame>& frames, std::size_t angles, std::size_t k,
                const model::FrameSurface& surface, const model::FitOptions& o) {
  double sum = 0;
  for (std::size_t i = k; i < frames.size(); i += angles) {
    model::DrawnFrame frame = frames[i];
    frame.surface = &surface;
    sum += model::squared_error(fit.variant, fit.parameters, frame, o);
  }
  return sum;
}

// The angles with some light's frame drawn off on more than kPlaced of the share it allows.
std::vector<std::size_t> angles_to_place(const model::Fit& fit, const std::vector<model::DrawnFrame>& frames, std::size_t angles,
                                         const model::FitOptions& o) {
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < angles; ++k)
    for (std::size_t i = k; i < frames.size(); i += angles)
      if (model::failing_share(fit.variant, fit.parameters, frames[i], o) > kPlaced * frames[i].allowed) {
        out.push_back(k);
        break;
      }
  return out;
}

}  // namespace

double v_point(double below, double at, double above, double reach) {
  const double slope = (std::max(below, above) - at) / reach;
  if (slope <= 0) return below < above ? -reach : (above < below ? reach : 0.0);
  return std::clamp((below - above) / (2 * slope), -reach, reach);
}

std::optional<EdgePlacement> placed_by_edges(const model::Fit& fit, const std::vector<model::DrawnFrame>& frames, std::size_t angles,
                                             const model::FitOptions& o, const MovedFlatColour& moved) {
  if (angles == 0 || frames.size() < angles || !moved) return std::nullopt;
  const std::vector<std::size_t> off = angles_to_place(fit, frames, angles, o);
  if (off.empty()) return std::nullopt;
  // Each angle off, kEdgeReach before and after it: one render.
  std::vector<std::size_t> either_side;
  std::vector<double> reach;
  for (const std::size_t k : off) {
    either_side.insert(either_side.end(), {k, k});
    reach.insert(reach.end(), {-kEdgeReach, kEdgeReach});
  }
  const auto sides = moved(either_side, reach);
  if (!sides || sides->size() != either_side.size()) return std::nullopt;
  EdgePlacement out{std::vector<double>(angles, 0.0), {}};
  for (std::size_t j = 0; j < off.size(); ++j) {
    const std::size_t k = off[j];
    const double below = error_at(fit, frames, angles, k, with_flat_colour(*frames[k].surface, *(*sides)[2 * j]), o);
    const double above = error_at(fit, frames, angles, k, with_flat_colour(*frames[k].surface, *(*sides)[2 * j + 1]), o);
    out.offsets[k] = v_point(below, error_at(fit, frames, angles, k, *frames[k].surface, o), above, kEdgeReach);
  }
  std::vector<double> points;
  for (const std::size_t k : off) points.push_back(out.offsets[k]);
  const auto placed = moved(off, points);
  if (!placed || placed->size() != off.size()) return std::nullopt;
  for (std::size_t k = 0; k < angles; ++k) out.surfaces.push_back(*frames[k].surface);
  for (std::size_t j = 0; j < off.size(); ++j) model::add_quantity(out.surfaces[off[j]], *(*placed)[j], model::Quantity::flat_colour);
  return out;
}

}  // namespace shadelab::grade
