#pragma once
// The submission sheet as one self-contained HTML page (the grids embedded as data: URIs): the
// same sections as the PDF, for a browser or an LMS. Deterministic for the same Sheet.
#include <string>

#include "sheet/sheet.h"

namespace shadelab::sheet {

std::string render_html(const Sheet& sheet);

}  // namespace shadelab::sheet
