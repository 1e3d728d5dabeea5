#pragma once
// The homework's formula as a model with named parts: ambient + light ⊙ (diffuse · max(N·L, 0) +
// specular · max(R·V, 0)^α), the specular term only where N·L > 0, with V from the point to the
// eye at the origin and R = reflect(-L, N); and the structural variants students write instead,
// each the formula with one thing changed. Evaluated per pixel from the reference's geometry
// (model/surface.h), so a failing submission's frames can be matched against every variant
// without a render of its own.
#include <array>
#include <optional>
#include <span>
#include <string_view>

#include <glm/vec3.hpp>

#include "model/surface.h"

namespace shadelab::model {

// Which terms a checkpoint's formula has: ambient + diffuse; ambient + diffuse + specular; or the
// normals deliverable's colour, normalize(abs(N)) per vertex, interpolated (no light, no colours).
enum class Terms { lambert, phong, normal_colour };
std::string_view to_string(Terms terms);  // "lambert", "phong", "normalColour" (a course profile's words)
std::optional<Terms> terms_named(std::string_view name);

// One change to the formula. The table in lighting.cpp gives each its id and words.
enum class Variant {
  formula,                     // as the homework writes it
  light_as_direction,          // L = normalize(light position): the position used as a direction
  view_away,                   // V = normalize(position): pointing away from the eye
  fixed_view,                  // V = (0, 0, 1) everywhere
  unnormalized_normal,         // N = the interpolated normal, not normalized
  flat_normal,                 // N = one normal per triangle
  negated_normal,              // N = -normalize(normal)
  unclamped_diffuse,           // N·L without max(…, 0)
  half_vector,                 // max(N·H, 0)^α with H = normalize(L + V) (Blinn)
  reflect_sign,                // R = reflect(L, N)
  unguarded_specular,          // the specular term also where N·L <= 0
  no_light_colour,             // neither term multiplied by the light's colour
  specular_without_light_colour,  // the specular term not multiplied by it
  // The normal's colour (Terms::normal_colour):
  missing_abs,                 // the normal itself, negative components clamped to black
  offset_normal,               // 0.5 N + 0.5
  flat_colour,                 // one colour per triangle, the provoking vertex's
  fragment_colour,             // normalize(abs(N)) per fragment, of the interpolated normal
  swapped_red_blue,            // (b, g, r) of the colour
  swapped_red_green,           // (g, r, b)
  swapped_green_blue,          // (r, b, g)
  rotated_channels,            // (g, b, r)
  rotated_channels_back,       // (b, r, g)
};

// Which formulas a variant changes: every one (the formula itself), the lighting's (a lambert or
// phong checkpoint), the specular term's alone, or the normal's colour.
enum class Applies { every, lighting, specular, normal_colour };

struct VariantInfo {
  Variant variant;
  std::string_view id;      // in a report: "light_as_direction"
  std::string_view label;   // for a TA's count of a class: "light used as a direction"
  Applies applies;
  // What the student's code does and what the homework's does, in the homework's terms. {light},
  // {position}, {normal}, {colour} and {light colour} stand for the course's names of the light's
  // position uniform, the position, normal and colour varyings and the light's colour uniform.
  std::string_view does, should;
};

std::span<const VariantInfo> variants();
const VariantInfo& info(Variant variant);
bool applies_to(const VariantInfo& variant, Terms terms);
std::optional<Variant> variant_named(std::string_view id);

// The values a fit finds, by the names a report and a course profile give them.
enum class Parameter { ambient, diffuse, specular, exponent, light_position };
std::string_view to_string(Parameter parameter);  // "ambient", ..., "lightPosition"
std::optional<Parameter> parameter_named(std::string_view name);

struct Light {
  glm::vec3 position;  // eye space
  glm::vec3 colour;
};

// The specular term at one sample of a pixel: the cosine before the exponent (max(R·V, 0) in the
// formula) and whether the term is added there.
struct SpecularSample {
  float c = 0;
  bool on = false;
};

// What the colours multiply at one point (or, for the normal's colour, the colour itself): colour =
// ambient + diffuse_light ⊙ diffuse · d + specular_light ⊙ specular · mean over the samples of
// (on ? c^α : 0). The colours enter linearly (the fit's least squares), the exponent through the
// cosines alone. One sample but where the pixel's samples see different triangles' flat normals:
// the rasteriser shades each triangle once and the resolve averages the shades, which no shade of
// an averaged normal is once the exponent bends it.
struct Factors {
  float d = 0;  // the diffuse factor, max(N·L, 0) in the formula (averaged over the samples)
  std::array<SpecularSample, kMaxSamples> specular{};
  int samples = 1;
  glm::vec3 diffuse_light{1}, specular_light{1};
  glm::vec3 colour{0};  // a normal-colour checkpoint's colour (no light, no colours to fit)
};

// `samples`: the point's flat normal at each of its pixel's samples (FrameSurface::samples_of),
// which flat normals are shaded with one by one; empty: the averaged flat normal.
Factors factors(Variant variant, const SurfacePoint& point, const Light& light, std::span<const glm::vec3> samples = {});

// The specular factor for exponent `alpha`, as GLSL's pow() computes it for a cosine in [0, 1],
// averaged over the samples.
float specular_factor(const Factors& f, float alpha);

}  // namespace shadelab::model
