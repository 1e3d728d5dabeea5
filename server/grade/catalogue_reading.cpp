#include "grade/catalogue_reading.h"

#include <algorithm>
#include <cmath>

#include "grade/diagnosis.h"
#include "grade/formula_readings.h"
#include "grade/starter_constants.h"

namespace shadelab::grade {

namespace {

// Whether a fitted value is a reading's, within what the frames tell apart: a colour's step, the
// exponent's 5%, a position's 5% of each coordinate (of 1 at least).
bool close_enough(model::Parameter parameter, double fitted, double wanted) {
  const double off = std::abs(fitted - wanted);
  switch (parameter) {
    case model::Parameter::exponent: return off <= kExponentTolerance * wanted;
    case model::Parameter::light_position: return off <= kPositionTolerance * std::max(1.0, std::abs(wanted));
    default: return off <= kColourTolerance;
  }
}

// The catalogued mistake that is `constant` at `value` and nothing else, if any.
const Mistake* catalogued_constant(const std::vector<Mistake>& mistakes, const StarterConstant& constant, double value) {
  for (const auto& m : mistakes) {
    if (!m.reading || m.reading->variant != model::Variant::formula || m.reading->values.size() != 1) continue;
    const auto& v = m.reading->values.front();
    if (to_string(v.parameter) == constant.meaning && v.value.size() == 1 && v.value.front() == value) return &m;
  }
  return nullptr;
}

}  // namespace

bool reads_as(const Explanation& e, const FormulaReading& reading) {
  const std::string variant(model::info(reading.variant).id);
  const bool also = reading.values.empty() && std::find(e.also_fits.begin(), e.also_fits.end(), variant) != e.also_fits.end();
  if (!e.explained || (e.variant != variant && !also) || e.parameters.size() != reading.values.size()) return false;
  for (const auto& want : reading.values) {
    const auto found = std::find_if(e.parameters.begin(), e.parameters.end(),
                                    [&](const Explanation::Parameter& p) { return p.name == to_string(want.parameter); });
    if (found == e.parameters.end() || found->fitted.size() != want.value.size()) return false;
    for (std::size_t i = 0; i < want.value.size(); ++i)
      if (!close_enough(want.parameter, found->fitted[i], want.value[i])) return false;
  }
  return true;
}

CatalogueWork catalogue_work(const std::vector<Mistake>& mistakes, const std::optional<Explanation>& e) {
  CatalogueWork out;
  for (const auto& m : mistakes) {
    if (!e || !e->explained || !m.reading) out.to_render.push_back(&m);
    else if (!out.recognised && reads_as(*e, *m.reading)) out.recognised = &m;
  }
  return out;
}

void name_catalogued_constants(Report& report, const GradeSpec& spec, const std::string& fragment) {
  for (const auto& found : changed_starter_constants(spec.starter_constants, fragment)) {
    if (report.diagnosis != changed_constant_diagnosis(found.variable)) continue;
    const auto constant = std::find_if(spec.starter_constants.begin(), spec.starter_constants.end(),
                                       [&](const StarterConstant& c) { return c.variable == found.variable; });
    const Mistake* m = catalogued_constant(spec.mistakes, *constant, found.value);
    if (!m) continue;
    report.diagnosis = m->id;
    std::replace(report.messages.begin(), report.messages.end(), found.message, m->message);
  }
}

std::optional<RenderedMistake> recognised_mistake(const CatalogueWork& work) {
  if (!work.recognised) return std::nullopt;
  return RenderedMistake{work.recognised->id, work.recognised->message, {}};
}

}  // namespace shadelab::grade
