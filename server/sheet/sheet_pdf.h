#pragma once
// The submission sheet as a PDF (cairo): A4, one section per checkpoint (its title, the grader's
// verdict, the grid, then the shader code with line numbers, wrapped, the lines the grader points
// at marked), then the answers. The same Sheet gives the same bytes: the PDF carries no date.
#include <string>

#include "core/expected.h"
#include "sheet/sheet.h"

namespace shadelab::sheet {

// Errors: io_error (cairo failed); a grid that is not a PNG is drawn as a note instead.
Expected<std::string> render_pdf(const Sheet& sheet);

}  // namespace shadelab::sheet
