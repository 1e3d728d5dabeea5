#include "grade/catalogue_reading.h"

#include <algorithm>
#include <cmath>

#include "grade/formula_readings.h"

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

std::optional<RenderedMistake> recognised_mistake(const CatalogueWork& work) {
  if (!work.recognised) return std::nullopt;
  return RenderedMistake{work.recognised->id, work.recognised->message, {}};
}

}  // namespace shadelab::grade
