#include "repair/value_change.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace shadelab::repair {

namespace {

using K = RepairKind;
using Rgb = std::array<float, 3>;

struct ChangeRow {
  ValueChange change;
  std::span<const RepairKind> kinds;
};

constexpr RepairKind kNegating[] = {K::negation_added, K::negation_removed, K::operator_swapped};
constexpr RepairKind kNormalising[] = {K::normalised};
constexpr RepairKind kUnnormalising[] = {K::unnormalised};
constexpr RepairKind kClamping[] = {K::clamped};
// A factor: one the reference multiplies by put back or one the student put in taken out, a
// colour named for another, a number refitted.
constexpr RepairKind kScaling[] = {K::factor_added, K::factor_removed, K::name_replaced, K::literal_refit};
// A term: put back, taken out, a computed one added, a sign between two terms.
constexpr RepairKind kShifting[] = {K::term_added, K::term_removed, K::value_added, K::write_restored, K::operator_swapped};
constexpr RepairKind kPowering[] = {K::exponent_added, K::literal_refit, K::name_replaced};
constexpr RepairKind kSwizzling[] = {K::swizzle_removed};
// Another of the reference's values: the name read in place of the right one (`reflect(-L, L)`),
// or the value computed otherwise, put back whole.
constexpr RepairKind kReplacing[] = {K::name_replaced, K::value_restored};

// One row a change, in the enum's order.
constexpr ChangeRow kChanges[] = {
    {ValueChange::negated, kNegating},   {ValueChange::normalised, kNormalising}, {ValueChange::unnormalised, kUnnormalising},
    {ValueChange::clamped, kClamping},   {ValueChange::scaled, kScaling},         {ValueChange::shifted, kShifting},
    {ValueChange::powered, kPowering},   {ValueChange::swizzled, kSwizzling},     {ValueChange::replaced, kReplacing},
};
static_assert(std::size(kChanges) == std::size(kValueChangeNames));

bool same(const Rgb& a, const Rgb& b) { return same_value(a[0], b[0]) && same_value(a[1], b[1]) && same_value(a[2], b[2]); }

// Whether `f` turns every sample's student value into its reference value.
bool everywhere(std::span<const ValueSample> samples, const std::function<Rgb(const Rgb&)>& f) {
  return std::all_of(samples.begin(), samples.end(), [&](const ValueSample& s) { return same(f(s.student), s.reference); });
}

float length(const Rgb& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

Rgb scaled(const Rgb& v, float k) { return {v[0] * k, v[1] * k, v[2] * k}; }

// Each channel's ratio of the reference to the student where the student's is largest: the
// constant a factor would be (1 where the student's channel is 0 everywhere).
Rgb factor_of(std::span<const ValueSample> samples) {
  Rgb out{1, 1, 1};
  for (size_t c = 0; c < 3; ++c) {
    const auto largest = std::max_element(samples.begin(), samples.end(),
                                          [&](const ValueSample& a, const ValueSample& b) { return std::abs(a.student[c]) < std::abs(b.student[c]); });
    if (std::abs(largest->student[c]) > 1e-6f) out[c] = largest->reference[c] / largest->student[c];
  }
  return out;
}

// The power a sample's value nearest 0.5 (and between 0.05 and 0.95) is raised to in the
// reference's; none where no sample is so.
std::optional<float> power_of(std::span<const ValueSample> samples) {
  std::optional<float> out;
  float nearest = 1;
  for (const auto& s : samples)
    for (size_t c = 0; c < 3; ++c) {
      const float x = s.student[c], y = s.reference[c];
      if (x < 0.05f || x > 0.95f || y <= 0 || std::abs(x - 0.5f) >= nearest) continue;
      nearest = std::abs(x - 0.5f);
      out = std::log(y) / std::log(x);
    }
  return out;
}

bool holds(ValueChange change, std::span<const ValueSample> samples) {
  switch (change) {
    case ValueChange::negated: return everywhere(samples, [](const Rgb& v) { return scaled(v, -1); });
    case ValueChange::normalised:
      return everywhere(samples, [](const Rgb& v) { return length(v) > 0 ? scaled(v, 1 / length(v)) : v; });
    case ValueChange::unnormalised:
      return std::all_of(samples.begin(), samples.end(), [](const ValueSample& s) {
        const float n = length(s.reference);
        return n > 0 && same(s.student, scaled(s.reference, 1 / n));
      });
    case ValueChange::clamped:
      return everywhere(samples, [](const Rgb& v) { return Rgb{std::max(v[0], 0.f), std::max(v[1], 0.f), std::max(v[2], 0.f)}; });
    case ValueChange::scaled: {
      // A factor of -1 is a sign: negated says it.
      const Rgb k = factor_of(samples);
      if (same(k, {-1, -1, -1})) return false;
      return everywhere(samples, [&](const Rgb& v) { return Rgb{v[0] * k[0], v[1] * k[1], v[2] * k[2]}; });
    }
    case ValueChange::shifted: {
      const ValueSample& first = samples.front();
      const Rgb d{first.reference[0] - first.student[0], first.reference[1] - first.student[1], first.reference[2] - first.student[2]};
      return everywhere(samples, [&](const Rgb& v) { return Rgb{v[0] + d[0], v[1] + d[1], v[2] + d[2]}; });
    }
    case ValueChange::powered: {
      // A power of 1 keeps what is positive: with the negative clamped, that is a clamp.
      const auto a = power_of(samples);
      if (!a || same_value(*a, 1)) return false;
      return everywhere(samples, [&](const Rgb& v) {
        return Rgb{std::pow(std::max(v[0], 0.f), *a), std::pow(std::max(v[1], 0.f), *a), std::pow(std::max(v[2], 0.f), *a)};
      });
    }
    case ValueChange::swizzled: {
      constexpr std::array<std::array<int, 3>, 5> kOrders{{{0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
      return std::any_of(kOrders.begin(), kOrders.end(), [&](const auto& o) {
        return everywhere(samples, [&](const Rgb& v) { return Rgb{v[o[0]], v[o[1]], v[o[2]]}; });
      });
    }
    case ValueChange::replaced:
      return false;  // two values, not one changed: read off the agreement (repair::departures)
  }
  return false;
}

}  // namespace

bool same_value(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  if (std::isinf(a) || std::isinf(b)) return a == b;
  return std::abs(a - b) <= 1e-3f * std::max(1.0f, std::abs(b));
}

std::span<const RepairKind> kinds_making(ValueChange change) { return kChanges[static_cast<size_t>(change)].kinds; }

bool makes(RepairKind kind, ValueChange change) {
  const auto kinds = kinds_making(change);
  return std::find(kinds.begin(), kinds.end(), kind) != kinds.end();
}

std::vector<ValueChange> changes_between(std::span<const ValueSample> samples) {
  std::vector<ValueChange> out;
  if (samples.empty() || everywhere(samples, [](const Rgb& v) { return v; })) return out;
  for (const auto& row : kChanges)
    if (holds(row.change, samples)) out.push_back(row.change);
  return out;
}

}  // namespace shadelab::repair
