#pragma once
// The diagnoses the grader makes on its own, beside the course's catalogue of mistakes (each
// catalogued mistake's id is the course profile's): one table of ids and what each means
// (diagnosis.cpp), as core/error.cpp's table is for error codes. A report's `diagnosis` is one of
// these, a catalogued mistake's id, changed_<variable> for a starter constant, an error code, or "".
#include <optional>
#include <string>
#include <string_view>

namespace shadelab::grade {

enum class Diagnosis {
  nan,                      // NaN in the frames (the float census)
  swapped_channels,         // a permutation of the colour channels matches the reference
  frames_out_of_order,      // a saved frame shows another frame's rotation
  frames_of_another_shape,  // saved frames whose outline is not the mesh's
  edited_frames,            // some saved frames differ from what the code renders, the others match
  stale_frames,             // the code renders the reference, the saved frames are not what it renders
  frames_not_from_code,     // the saved frames are not what the code renders
  made_by_shadelab,         // saved frames ShadeLab drew, where the course wants them from its page
};

std::string to_string(Diagnosis diagnosis);            // its id in a report
std::optional<Diagnosis> diagnosis_named(std::string_view id);
std::string_view meaning(Diagnosis diagnosis);          // what it means, in a sentence (docs, the API)

// The id of a changed starter constant: changed_specularAlpha.
std::string changed_constant_diagnosis(const std::string& variable);

}  // namespace shadelab::grade
