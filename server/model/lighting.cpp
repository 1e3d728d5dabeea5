#include "model/lighting.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/enum_names.h"

namespace shadelab::model {

namespace {

constexpr EnumName<Terms> kTerms[] = {{Terms::lambert, "lambert"}, {Terms::phong, "phong"}, {Terms::normal_colour, "normalColour"}};

constexpr auto kEvery = Applies::every, kLighting = Applies::lighting, kSpecular = Applies::specular, kNormal = Applies::normal_colour;

constexpr EnumName<Parameter> kParameters[] = {{Parameter::ambient, "ambient"},
                                               {Parameter::diffuse, "diffuse"},
                                               {Parameter::specular, "specular"},
                                               {Parameter::exponent, "exponent"},
                                               {Parameter::light_position, "lightPosition"}};

constexpr VariantInfo kVariants[] = {
    {Variant::formula, "formula", "the formula", kEvery, "the homework's formula", "the homework's formula"},
    {Variant::light_as_direction, "light_as_direction", "light used as a direction", kLighting,
     "the light comes from the direction {light} at every point, as if far away, not from the position {light}",
     "L must point from the point to the light: normalize({light} - {position})"},
    {Variant::view_away, "view_away", "view vector away from the eye", kSpecular, "the view vector points away from the eye: V = normalize({position})",
     "V must point from the point to the eye at the origin: normalize(-{position})"},
    {Variant::fixed_view, "fixed_view", "fixed view vector", kSpecular, "the view vector is the same at every point, (0, 0, 1)",
     "V must point from each point to the eye at the origin: normalize(-{position})"},
    {Variant::unnormalized_normal, "unnormalized_normal", "normal not normalized", kLighting,
     "the normal is used as interpolated, shorter than 1 between the vertices", "N must be normalize({normal}) in the fragment shader"},
    {Variant::flat_normal, "flat_normal", "flat normals", kLighting, "the normal is one per triangle (flat shading)",
     "N must be interpolated across each triangle: remove `flat` from {normal}"},
    {Variant::negated_normal, "negated_normal", "normal negated", kLighting, "the normal points into the surface: the side facing the light is dark",
     "N must be normalize({normal}), not its negative"},
    {Variant::unclamped_diffuse, "unclamped_diffuse", "N.L not clamped", kLighting,
     "the diffuse term is N·L without max(N·L, 0): the side facing away from the light is darker than the ambient colour",
     "the diffuse term must be max(N·L, 0)"},
    {Variant::half_vector, "half_vector", "Blinn's half vector", kSpecular, "the highlight is Blinn's, max(N·H, 0)^α with H = normalize(L + V)",
     "the homework's highlight is Phong's: max(R·V, 0)^α with R = reflect(-L, N)"},
    {Variant::reflect_sign, "reflect_sign", "reflect(L, N)", kSpecular, "R = reflect(L, N) reflects the light's direction the wrong way round",
     "R must be reflect(-L, N): L points to the light, reflect() wants the direction the light travels"},
    {Variant::unguarded_specular, "unguarded_specular", "specular where N.L <= 0", kSpecular, "the specular term is added where N·L <= 0 too",
     "add the specular term only where N·L > 0"},
    {Variant::no_light_colour, "no_light_colour", "light's colour left out", kLighting, "neither term is multiplied by the light's colour {light colour}",
     "multiply the diffuse and the specular term by {light colour}"},
    {Variant::specular_without_light_colour, "specular_without_light_colour", "light's colour left out of the specular", kSpecular,
     "the specular term is not multiplied by the light's colour {light colour}", "multiply the specular term by {light colour} too"},
    {Variant::missing_abs, "missing_abs", "abs() missing", kNormal,
     "the colour is the normal itself, without abs(): every component that points away (x < 0, y < 0 or z < 0) shows as black",
     "{colour} must be normalize(abs(N)): each component's size, whichever way it points"},
    {Variant::offset_normal, "offset_normal", "0.5 N + 0.5", kNormal, "the colour is 0.5·N + 0.5, the normal mapped to [0, 1]",
     "{colour} must be normalize(abs(N)): each component's size, whichever way it points"},
    {Variant::flat_colour, "flat_colour", "flat colour", kNormal, "the colour is one per triangle (flat shading)",
     "{colour} must be interpolated across each triangle: remove `flat` from it"},
    {Variant::fragment_colour, "fragment_colour", "colour per fragment", kNormal,
     "the colour is computed per fragment, from the normal as interpolated",
     "compute normalize(abs(N)) once per vertex, in the vertex shader, and interpolate {colour}"},
    {Variant::swapped_red_blue, "swapped_red_blue", "red and blue swapped", kNormal,
     "red and blue are swapped: red shows the normal's z and blue its x", "red, green and blue must show the normal's x, y and z"},
    {Variant::swapped_red_green, "swapped_red_green", "red and green swapped", kNormal,
     "red and green are swapped: red shows the normal's y and green its x", "red, green and blue must show the normal's x, y and z"},
    {Variant::swapped_green_blue, "swapped_green_blue", "green and blue swapped", kNormal,
     "green and blue are swapped: green shows the normal's z and blue its y", "red, green and blue must show the normal's x, y and z"},
    {Variant::rotated_channels, "rotated_channels", "channels rotated", kNormal,
     "the channels are rotated: red shows the normal's y, green its z and blue its x", "red, green and blue must show the normal's x, y and z"},
    {Variant::rotated_channels_back, "rotated_channels_back", "channels rotated", kNormal,
     "the channels are rotated: red shows the normal's z, green its x and blue its y", "red, green and blue must show the normal's x, y and z"},
};

static_assert(std::size(kVariants) == static_cast<std::size_t>(Variant::rotated_channels_back) + 1);

// GLSL's reflect(I, N) = I - 2 dot(N, I) N, for an N of any length as the shader passes it.
glm::vec3 reflect(const glm::vec3& i, const glm::vec3& n) { return i - 2.0f * glm::dot(n, i) * n; }

glm::vec3 normal_of(Variant v, const SurfacePoint& p) {
  switch (v) {
    case Variant::unnormalized_normal: return p.normal;
    case Variant::flat_normal: return glm::normalize(p.flat_normal);
    case Variant::negated_normal: return -glm::normalize(p.normal);
    default: return glm::normalize(p.normal);
  }
}

glm::vec3 view_of(Variant v, const SurfacePoint& p) {
  switch (v) {
    case Variant::view_away: return glm::normalize(p.position);
    case Variant::fixed_view: return {0, 0, 1};
    default: return glm::normalize(-p.position);
  }
}

// The normal's colour as `v` computes it. The mesh's normals are unit length: the colour without
// abs() (normalize per vertex, then interpolated) is the interpolated normal. The flat colour is
// its own render's: where a pixel holds several triangles, the average of their colours, which no
// colour of one averaged normal is.
glm::vec3 colour_of(Variant v, const SurfacePoint& p) {
  const glm::vec3 c = p.colour;
  switch (v) {
    case Variant::missing_abs: return p.normal;
    case Variant::offset_normal: return 0.5f * p.normal + 0.5f;
    case Variant::flat_colour: return p.flat_colour;
    case Variant::fragment_colour: return glm::abs(glm::normalize(p.normal));
    case Variant::swapped_red_blue: return {c.b, c.g, c.r};
    case Variant::swapped_red_green: return {c.g, c.r, c.b};
    case Variant::swapped_green_blue: return {c.r, c.b, c.g};
    case Variant::rotated_channels: return {c.g, c.b, c.r};
    case Variant::rotated_channels_back: return {c.b, c.r, c.g};
    default: return c;
  }
}

}  // namespace

std::string_view to_string(Terms terms) { return name_in(kTerms, terms); }
std::optional<Terms> terms_named(std::string_view name) { return value_in(kTerms, name); }

std::span<const VariantInfo> variants() { return kVariants; }
const VariantInfo& info(Variant variant) { return kVariants[static_cast<std::size_t>(variant)]; }
bool applies_to(const VariantInfo& v, Terms terms) {
  switch (v.applies) {
    case Applies::every: return true;
    case Applies::lighting: return terms != Terms::normal_colour;
    case Applies::specular: return terms == Terms::phong;
    case Applies::normal_colour: return terms == Terms::normal_colour;
  }
  return false;
}

std::optional<Variant> variant_named(std::string_view id) {
  for (const auto& v : kVariants)
    if (v.id == id) return v.variant;
  return std::nullopt;
}

std::string_view to_string(Parameter parameter) { return name_in(kParameters, parameter); }
std::optional<Parameter> parameter_named(std::string_view name) { return value_in(kParameters, name); }

namespace {

struct Shading {
  float d;
  SpecularSample specular;
};

// The diffuse factor and the specular term of `v` at `p` with the normal `n`. Inlined: it runs
// for every pixel of every frame a fit is checked on.
[[gnu::always_inline]] inline Shading shading(Variant v, const glm::vec3& n, const SurfacePoint& p, const Light& light) {
  const glm::vec3 l = glm::normalize(v == Variant::light_as_direction ? light.position : light.position - p.position);
  const glm::vec3 e = view_of(v, p);
  const float n_dot_l = glm::dot(n, l);
  Shading s{};
  s.d = v == Variant::unclamped_diffuse ? n_dot_l : std::max(0.0f, n_dot_l);
  if (v == Variant::half_vector)
    s.specular.c = std::max(0.0f, glm::dot(n, glm::normalize(l + e)));
  else
    s.specular.c = std::max(0.0f, glm::dot(e, reflect(v == Variant::reflect_sign ? l : -l, n)));
  s.specular.on = v == Variant::unguarded_specular || n_dot_l > 0;
  return s;
}

// Flat normals where a pixel's samples see different triangles: each sample shaded with its own
// triangle's normal, at the pixel's position, the diffuse factor averaged. Apart from factors(), so
// that the one shading every other pixel and variant takes stays inlined there.
[[gnu::noinline]] void shade_samples(Factors& f, const SurfacePoint& p, const Light& light, std::span<const glm::vec3> n) {
  f.samples = static_cast<int>(std::min<std::size_t>(n.size(), kMaxSamples));
  for (std::size_t i = 0; i < static_cast<std::size_t>(f.samples); ++i) {
    const Shading s = shading(Variant::flat_normal, glm::normalize(n[i]), p, light);
    f.d += s.d / static_cast<float>(f.samples);
    f.specular[i] = s.specular;
  }
}

bool differ(std::span<const glm::vec3> n) {
  return std::any_of(n.begin(), n.end(), [&](const glm::vec3& m) { return m != n[0]; });
}

}  // namespace

Factors factors(Variant v, const SurfacePoint& p, const Light& light, std::span<const glm::vec3> n) {
  // One object returned on every path: built in the caller's, not copied there field by field
  // after (a copy that stalled on its own stores, half of this function's time).
  Factors f;
  if (info(v).applies == Applies::normal_colour) {
    f.colour = colour_of(v, p);
    return f;
  }
  const bool sampled = v == Variant::flat_normal && !n.empty();
  if (sampled && differ(n)) {
    shade_samples(f, p, light, n);
  } else {
    // A pixel inside one triangle: its samples' normal is the triangle's.
    const Shading s = shading(v, sampled ? glm::normalize(n[0]) : normal_of(v, p), p, light);
    f.d = s.d;
    f.specular[0] = s.specular;
  }
  f.diffuse_light = v == Variant::no_light_colour ? glm::vec3(1) : light.colour;
  f.specular_light = v == Variant::no_light_colour || v == Variant::specular_without_light_colour ? glm::vec3(1) : light.colour;
  f.colour = p.colour;
  return f;
}

namespace {

float mean_over_samples(const Factors& f, float alpha) {
  float sum = 0;
  for (std::size_t i = 0; i < static_cast<std::size_t>(f.samples); ++i)
    if (const SpecularSample& s = f.specular[i]; s.on) sum += std::pow(s.c, alpha);
  return sum / static_cast<float>(f.samples);
}

}  // namespace

float specular_factor(const Factors& f, float alpha) {
  if (f.samples > 1) return mean_over_samples(f, alpha);
  return f.specular[0].on ? std::pow(f.specular[0].c, alpha) : 0.0f;
}

}  // namespace shadelab::model
