#pragma once
// How a departing value differs from its counterpart's, read off the two values at every pixel
// both drew (issue 79, "edits from values"): the reference's value is the student's negated,
// normalised, clamped at 0, times a constant, plus a constant, raised to a constant power or with
// its channels reordered. The worker reads these beside the values' agreement
// (grade/value_reading.h) on the CPU, before any candidate is drawn; the search then screens
// first, at a line where a value departs, the edits whose kind makes that change there
// (repair/search_order.h). A change is only an order: a render still confirms every repair.
#include <array>
#include <span>
#include <vector>

#include "core/enum_names.h"
#include "repair/repair_kind.h"

namespace shadelab::repair {

// What turns the student's value into the reference's, at every pixel both drew.
enum class ValueChange {
  negated,       // -s
  normalised,    // normalize(s)
  unnormalised,  // the reference's is s's direction at another length
  clamped,       // max(s, 0.0)
  scaled,        // s times a constant (a colour, a number): a factor left out or put in
  shifted,       // s plus a constant: a term left out or put in
  powered,       // s to a constant power: an exponent left out or changed
  swizzled,      // s's channels in another order
  replaced,      // s is another of the reference's values (`V` computed as `L`, `reflect(-L, L)`): a name or the value put back
};
inline constexpr EnumName<ValueChange> kValueChangeNames[] = {
    {ValueChange::negated, "negated"}, {ValueChange::normalised, "normalised"}, {ValueChange::unnormalised, "unnormalised"},
    {ValueChange::clamped, "clamped"}, {ValueChange::scaled, "scaled"},         {ValueChange::shifted, "shifted"},
    {ValueChange::powered, "powered"}, {ValueChange::swizzled, "swizzled"},         {ValueChange::replaced, "replaced"},
};

// The kinds of edit that make `change` at the line they edit (a value restored whole can make any
// change, and is in no row but `replaced`'s: elsewhere it keeps its place in the search's order).
std::span<const RepairKind> kinds_making(ValueChange change);
bool makes(RepairKind kind, ValueChange change);

// One pixel both programs drew: the student's value and the reference's (rgb; a float's value is
// in each channel).
struct ValueSample {
  std::array<float, 3> student, reference;
};

// Whether two floats are one value within what float arithmetic done otherwise gives (another
// order, a fused multiply-add): a thousandth of the value, or of 1 below it.
bool same_value(float a, float b);

// The changes that turn every sample's student value into its reference value, within what float
// arithmetic done otherwise gives; none where the two are the same at every sample (nothing to
// change) or there are no samples.
std::vector<ValueChange> changes_between(std::span<const ValueSample> samples);

// One student value's change to one of the reference's values (its probe's index).
struct ValueChangeTo {
  int reference = 0;
  ValueChange change = ValueChange::negated;
};

}  // namespace shadelab::repair
