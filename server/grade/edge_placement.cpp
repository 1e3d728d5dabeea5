#include "grade/edge_placement.h"

#include <algorithm>

namespace shadelab::grade {

namespace {

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

// The flat colour rendered at each angle moved by its offset, one surface per angle.
std::optional<std::vector<model::FrameSurface>> moved_surfaces(const std::vector<model::DrawnFrame>& frames, std::size_t angles,
                                                               const std::vector<double>& offsets, const MovedFlatColour& moved) {
  auto rendered = moved(offsets);
  if (!rendered || rendered->size() != angles) return std::nullopt;
  std::vector<model::FrameSurface> out;
  for (std::size_t k = 0; k < angles; ++k) out.push_back(with_flat_colour(*frames[k].surface, *(*rendered)[k]));
  return out;
}

// Each angle's error with the flat colour at `offset` from it.
std::optional<std::vector<double>> errors_moved(const model::Fit& fit, const std::vector<model::DrawnFrame>& frames, std::size_t angles,
                                                double offset, const model::FitOptions& o, const MovedFlatColour& moved) {
  const auto surfaces = moved_surfaces(frames, angles, std::vector<double>(angles, offset), moved);
  if (!surfaces) return std::nullopt;
  std::vector<double> out;
  for (std::size_t k = 0; k < angles; ++k) out.push_back(error_at(fit, frames, angles, k, (*surfaces)[k], o));
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
  const auto below = errors_moved(fit, frames, angles, -kEdgeReach, o, moved);
  if (!below) return std::nullopt;
  const auto above = errors_moved(fit, frames, angles, kEdgeReach, o, moved);
  if (!above) return std::nullopt;
  EdgePlacement out;
  for (std::size_t k = 0; k < angles; ++k)
    out.offsets.push_back(v_point((*below)[k], error_at(fit, frames, angles, k, *frames[k].surface, o), (*above)[k], kEdgeReach));
  auto surfaces = moved_surfaces(frames, angles, out.offsets, moved);
  if (!surfaces) return std::nullopt;
  out.surfaces = std::move(*surfaces);
  return out;
}

}  // namespace shadelab::grade
