#pragma once
// The course's catalogue of mistakes read by the formula: a catalogued mistake with a reading
// (the formula's variant and values it draws) is recognised from the explanation alone, with no
// render of its own; the others are rendered and compared (grade/grader.h).
#include <optional>
#include <vector>

#include "grade/grade_spec.h"
#include "grade/report.h"

namespace shadelab::grade {

// Whether an explanation is `reading`: it explains, by the reading's variant (or by one that fits
// as well, where the reading changes no value), with the same values changed, each within what the
// frames tell apart.
bool reads_as(const Explanation& explanation, const FormulaReading& reading);

// The known mistakes a failing grade still renders, and the one the formula's reading recognised.
// Where the formula explains the frames, a mistake with a reading needs no render: it is recognised
// when the explanation is its reading, and is not the frames otherwise (the formula's change draws
// them). Where the formula explains nothing (or read nothing: no formula, frames too small), every
// mistake is rendered and compared: a reading that just misses (another rasteriser's frames) must
// not lose the catalogue's diagnosis.
struct CatalogueWork {
  const Mistake* recognised = nullptr;
  std::vector<const Mistake*> to_render;
};
CatalogueWork catalogue_work(const std::vector<Mistake>& mistakes, const std::optional<Explanation>& explanation);
// A changed starter constant the catalogue names, in its words: a mistake whose reading (the
// formula's own variant) changes the constant's quantity alone, to the value the student's
// `fragment` gives it (the handout's exponent, 0.6). The source says it exactly: no render, no
// formula. `report` (a failing grade's, its diagnosis changed_<variable>) then carries the
// mistake's id and message in place of the constant's.
void name_catalogued_constants(Report& report, const GradeSpec& spec, const std::string& fragment);

// The recognised mistake as grade::explain takes it (no frames), if any.
std::optional<RenderedMistake> recognised_mistake(const CatalogueWork& work);

}  // namespace shadelab::grade
