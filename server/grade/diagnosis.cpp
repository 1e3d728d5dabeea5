#include "grade/diagnosis.h"

#include <cstddef>

namespace shadelab::grade {

namespace {

struct Row {
  Diagnosis value;
  std::string_view id, meaning;
};

// In the enum's order.
constexpr Row kDiagnoses[] = {
    {Diagnosis::nan, "nan", "the frames hold NaN, which the browser shows black or transparent"},
    {Diagnosis::swapped_channels, "swapped_channels", "a permutation of the colour channels matches the reference"},
    {Diagnosis::frames_out_of_order, "frames_out_of_order", "a saved frame shows another frame's rotation: saved out of order, or twice"},
    {Diagnosis::frames_of_another_shape, "frames_of_another_shape",
     "the saved frames' outline is not the mesh's: saved with another mesh selected"},
    {Diagnosis::edited_frames, "edited_frames", "some saved frames differ from what the code renders, the others match"},
    {Diagnosis::stale_frames, "stale_frames", "the code renders the reference, but the saved frames are not what it renders"},
    {Diagnosis::frames_not_from_code, "frames_not_from_code", "the saved frames are not what the code renders"},
    {Diagnosis::made_by_shadelab, "made_by_shadelab", "the saved frames are ShadeLab's own render, not the page's"},
};

const Row& row(Diagnosis d) { return kDiagnoses[static_cast<std::size_t>(d)]; }

}  // namespace

std::string to_string(Diagnosis diagnosis) { return std::string(row(diagnosis).id); }

std::optional<Diagnosis> diagnosis_named(std::string_view id) {
  for (const auto& r : kDiagnoses)
    if (r.id == id) return r.value;
  return std::nullopt;
}

std::string_view meaning(Diagnosis diagnosis) { return row(diagnosis).meaning; }
std::string changed_constant_diagnosis(const std::string& variable) { return "changed_" + variable; }

}  // namespace shadelab::grade
