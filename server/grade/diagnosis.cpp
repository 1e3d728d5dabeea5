#include "grade/diagnosis.h"

#include "core/enum_names.h"

namespace shadelab::grade {

namespace {

constexpr EnumName<Diagnosis> kIds[] = {
    {Diagnosis::nan, "nan"},
    {Diagnosis::swapped_channels, "swapped_channels"},
    {Diagnosis::frames_out_of_order, "frames_out_of_order"},
    {Diagnosis::frames_of_another_shape, "frames_of_another_shape"},
    {Diagnosis::edited_frames, "edited_frames"},
    {Diagnosis::stale_frames, "stale_frames"},
    {Diagnosis::frames_not_from_code, "frames_not_from_code"},
    {Diagnosis::made_by_shadelab, "made_by_shadelab"},
};

constexpr EnumName<Diagnosis> kMeanings[] = {
    {Diagnosis::nan, "the frames hold NaN, which the browser shows black or transparent"},
    {Diagnosis::swapped_channels, "a permutation of the colour channels matches the reference"},
    {Diagnosis::frames_out_of_order, "a saved frame shows another frame's rotation: saved out of order, or twice"},
    {Diagnosis::frames_of_another_shape, "the saved frames' outline is not the mesh's: saved with another mesh selected"},
    {Diagnosis::edited_frames, "some saved frames differ from what the code renders, the others match"},
    {Diagnosis::stale_frames, "the code renders the reference, but the saved frames are not what it renders"},
    {Diagnosis::frames_not_from_code, "the saved frames are not what the code renders"},
    {Diagnosis::made_by_shadelab, "the saved frames are ShadeLab's own render, not the page's"},
};

}  // namespace

std::string to_string(Diagnosis diagnosis) { return std::string(name_in(kIds, diagnosis)); }
std::optional<Diagnosis> diagnosis_named(std::string_view id) { return value_in(kIds, id); }
std::string_view meaning(Diagnosis diagnosis) { return name_in(kMeanings, diagnosis); }
std::string changed_constant_diagnosis(const std::string& variable) { return "changed_" + variable; }

}  // namespace shadelab::grade
