#pragma once
// The vectors of the homework's formula (the handout's N, L, V and R), each with the words a
// repair says it in. A course profile names which of its reference's locals is which
// (`formula.vectors`, docs/course-profile.md), so a repair at a student's own name for one says
// what it is in the homework's terms: "`toEye`, the direction to the eye, has the wrong sign";
// "`L` is not normalised: the direction to the light must be a unit vector".
#include <functional>
#include <map>
#include <string>
#include <string_view>

#include "core/enum_names.h"

namespace shadelab::grade {

enum class FormulaVector { normal, light, view, reflected };
inline constexpr EnumName<FormulaVector> kFormulaVectorNames[] = {
    {FormulaVector::normal, "normal"},
    {FormulaVector::light, "light"},
    {FormulaVector::view, "view"},
    {FormulaVector::reflected, "reflected"},
};
inline constexpr EnumName<FormulaVector> kFormulaVectorWords[] = {
    {FormulaVector::normal, "the normal"},
    {FormulaVector::light, "the direction to the light"},
    {FormulaVector::view, "the direction to the eye"},
    {FormulaVector::reflected, "the direction to the light reflected about the normal"},
};

// The reference's locals that are the formula's vectors, each with its words: "V": "the
// direction to the eye" (a checkpoint's, road::vector_words).
using VectorWords = std::map<std::string, std::string, std::less<>>;

}  // namespace shadelab::grade
