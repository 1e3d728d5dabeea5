#pragma once
// The geometry under each pixel of a frame, as the reference's rasterisation has it: what the
// homework's formula (model/lighting.h) needs to shade the pixel on the CPU. Read from float renders
// of the reference's vertex shader (grade/formula_geometry.h): the eye-space position, the normal as
// interpolated (not normalized) and the normal as a `flat` varying gives it, and for a normal-colour
// checkpoint the colour its vertex shader computes, as interpolated and flat; each resolved over the frame's
// samples; the position's alpha is 1 + the share of samples the mesh covers. For a specular
// checkpoint, the flat normal at each sample besides (a render without MSAA at each sample's
// position). Kept as the object's pixels alone: a quarter of a homework frame.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "image/image.h"

namespace shadelab::model {

// The most samples of a pixel the surface keeps apart (MSAA 4, the browser's).
inline constexpr int kMaxSamples = 4;

struct SurfacePoint {
  glm::vec3 position;     // eye space (the eye at the origin)
  glm::vec3 normal;       // interpolated, as the fragment shader receives it before normalize()
  glm::vec3 flat_normal;  // the provoking vertex's, as a `flat` varying receives it (averaged over the samples)
  glm::vec3 colour{0};    // a normal-colour checkpoint's: the reference's per-vertex colour, interpolated
  glm::vec3 flat_colour{0};  // ... and as a `flat` varying gives it (averaged over the pixel's triangles)
};

// A frame's interior: the pixels every sample of which the mesh covers (an outline pixel is a
// blend of the object and the background the model does not draw), in row order.
struct FrameSurface {
  int width = 0, height = 0;
  std::vector<std::uint32_t> pixels;  // y * width + x, rows top-down as the frames'
  std::vector<SurfacePoint> points;   // one per pixel
  std::vector<std::uint32_t> outline; // the pixels the mesh covers in part
  // Where kept, the flat normal at each of a pixel's samples, each that of the triangle covering
  // it: kMaxSamples a point, `samples` of them read. Apart from the points, which every fit scans.
  std::vector<glm::vec3> sample_flat_normals;
  int samples = 0;

  // Point i's flat normal sample by sample; empty where none are kept.
  std::span<const glm::vec3> samples_of(std::size_t i) const {
    if (samples == 0) return {};
    return {sample_flat_normals.data() + i * kMaxSamples, static_cast<std::size_t>(samples)};
  }
  std::size_t bytes() const {
    return pixels.size() * 4 + points.size() * sizeof(SurfacePoint) + outline.size() * 4 + sample_flat_normals.size() * sizeof(glm::vec3);
  }
};

// A surface's pixels and positions from the position render (RGBA32F)...
FrameSurface surface_from(const image::Image& position);
// ...then each other quantity from its render (the same size).
// A sample's flat normal comes from a render without MSAA at that sample's position (`sample`:
// which); a sample its render does not cover keeps the pixel's averaged flat normal.
enum class Quantity { position, normal, flat_normal, colour, flat_colour, sample_flat_normal };
void add_quantity(FrameSurface& surface, const image::Image& render, Quantity quantity, int sample = 0);

}  // namespace shadelab::model
